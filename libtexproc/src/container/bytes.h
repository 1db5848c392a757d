// Little-endian byte writing and bounds-checked reading for the containers.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "texproc/error.h"

namespace texproc {

// A file's bytes as written: fields and padding owned here, and large
// payloads (a texture's images) by reference, so a file can go to disk
// without first being copied into one buffer. Offsets are logical (the
// file's); put_*_at may patch only owned bytes.
class ByteWriter {
 public:
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { raw(&v, 2); }
  void u32(std::uint32_t v) { raw(&v, 4); }
  void u64(std::uint64_t v) { raw(&v, 8); }
  void raw(const void* p, std::size_t n) {  // little-endian host (x86-64, Arm64)
    if (n == 0) return;
    const std::size_t at = out_.size();
    out_.resize(at + n);  // (not insert: GCC 12 warns falsely of an overflow in vector::insert here)
    std::memcpy(out_.data() + at, p, n);
  }
  // `n` bytes at `p`, which must stay valid while this writer is used.
  void ref(const void* p, std::size_t n) {
    if (n < 4096) return raw(p, n);
    refs_.push_back({out_.size(), static_cast<const std::uint8_t*>(p), n});
    referenced_ += n;
  }
  void zeros(std::size_t n) { out_.insert(out_.end(), n, 0); }
  void pad_to(std::size_t alignment) {
    while (size() % alignment) out_.push_back(0);
  }
  void put_u32_at(std::size_t at, std::uint32_t v) { std::memcpy(out_.data() + owned_offset(at, 4), &v, 4); }
  void put_u64_at(std::size_t at, std::uint64_t v) { std::memcpy(out_.data() + owned_offset(at, 8), &v, 8); }
  std::size_t size() const { return out_.size() + referenced_; }
  // The whole file in one buffer.
  std::vector<std::uint8_t> bytes() && {
    if (refs_.empty()) return std::move(out_);
    std::vector<std::uint8_t> all;
    all.reserve(size());
    write_to([&](const std::uint8_t* p, std::size_t n) { all.insert(all.end(), p, p + n); });
    return all;
  }
  // Calls sink(pointer, length) for the file's bytes in order.
  template <typename Sink>
  void write_to(Sink&& sink) const {
    std::size_t owned = 0;
    for (const Ref& r : refs_) {
      if (r.owned_at > owned) sink(out_.data() + owned, r.owned_at - owned);
      owned = r.owned_at;
      sink(r.data, r.size);
    }
    if (out_.size() > owned) sink(out_.data() + owned, out_.size() - owned);
  }

 private:
  struct Ref {
    std::size_t owned_at;  // owned bytes before it
    const std::uint8_t* data;
    std::size_t size;
  };
  std::size_t owned_offset(std::size_t at, std::size_t n) const {
    std::size_t before = 0;  // referenced bytes before `at`
    for (const Ref& r : refs_) {
      const std::size_t logical = r.owned_at + before;
      if (at + n <= logical) break;
      if (at < logical + r.size)
        throw Error(ErrorCode::runtime, "container writer: a patch inside a referenced payload");
      before += r.size;
    }
    return at - before;
  }
  std::vector<std::uint8_t> out_;
  std::vector<Ref> refs_;
  std::size_t referenced_ = 0;
};

// Reads fields at checked offsets: every read names its field, and a read
// past the end throws Error{invalid_file} "<name>: truncated: <field>".
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size, std::string name)
      : data_(data), size_(size), name_(std::move(name)) {}
  std::size_t size() const { return size_; }
  const std::string& name() const { return name_; }
  const std::uint8_t* at(std::uint64_t offset, std::uint64_t length, const char* field) const {
    if (offset > size_ || length > size_ - offset) {
      fail(std::string("truncated: ") + field + " needs bytes " + std::to_string(offset) + ".." +
           std::to_string(offset + length) + " of " + std::to_string(size_));
    }
    return data_ + offset;
  }
  std::uint32_t u32(std::uint64_t offset, const char* field) const {
    std::uint32_t v;
    std::memcpy(&v, at(offset, 4, field), 4);
    return v;
  }
  std::uint64_t u64(std::uint64_t offset, const char* field) const {
    std::uint64_t v;
    std::memcpy(&v, at(offset, 8, field), 8);
    return v;
  }
  std::uint16_t u16(std::uint64_t offset, const char* field) const {
    std::uint16_t v;
    std::memcpy(&v, at(offset, 2, field), 2);
    return v;
  }
  [[noreturn]] void fail(const std::string& what) const { throw Error(ErrorCode::invalid_file, name_ + ": " + what); }
  [[noreturn]] void unsupported(const std::string& what) const {
    throw Error(ErrorCode::unsupported, name_ + ": " + what);
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::string name_;
};

}  // namespace texproc
