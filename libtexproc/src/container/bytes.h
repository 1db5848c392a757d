// Little-endian byte writing and bounds-checked reading for the containers.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "texproc/error.h"

namespace texproc {

class ByteWriter {
 public:
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { raw(&v, 2); }
  void u32(std::uint32_t v) { raw(&v, 4); }
  void u64(std::uint64_t v) { raw(&v, 8); }
  void raw(const void* p, std::size_t n) {  // little-endian host (x86-64, Arm64)
    const auto* b = static_cast<const std::uint8_t*>(p);
    out_.insert(out_.end(), b, b + n);
  }
  void zeros(std::size_t n) { out_.insert(out_.end(), n, 0); }
  void pad_to(std::size_t alignment) {
    while (out_.size() % alignment) out_.push_back(0);
  }
  void put_u32_at(std::size_t at, std::uint32_t v) { std::memcpy(out_.data() + at, &v, 4); }
  void put_u64_at(std::size_t at, std::uint64_t v) { std::memcpy(out_.data() + at, &v, 8); }
  std::size_t size() const { return out_.size(); }
  std::vector<std::uint8_t>& bytes() { return out_; }

 private:
  std::vector<std::uint8_t> out_;
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
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ErrorCode::invalid_file, name_ + ": " + what);
  }
  [[noreturn]] void unsupported(const std::string& what) const {
    throw Error(ErrorCode::unsupported, name_ + ": " + what);
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::string name_;
};

}  // namespace texproc
