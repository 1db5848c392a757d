// A BPTC block's 128 bits written from the lowest up (the order the
// decoders in bptc_decode.cpp read them), for the BC7 and BC6H packers.
#pragma once

#include <cstdint>
#include <cstring>

namespace texproc::bptc {

__extension__ typedef unsigned __int128 BlockBits;  // GCC's and Clang's 128-bit integer

class BitWriter {
 public:
  void write(std::uint32_t v, int n) {  // n <= 32 bits, v < 2^n: one 128-bit shift
    bits_ |= BlockBits(v) << pos_;
    pos_ += n;
  }
  void write64(std::uint64_t v, int n) {  // n <= 64 bits, v < 2^n
    bits_ |= BlockBits(v) << pos_;
    pos_ += n;
  }
  int position() const { return pos_; }
  void store(std::uint8_t out[16]) const {
    const std::uint64_t lo = std::uint64_t(bits_), hi = std::uint64_t(bits_ >> 64);
    std::memcpy(out, &lo, 8);  // little-endian hosts (as the rest of texproc)
    std::memcpy(out + 8, &hi, 8);
  }

 private:
  BlockBits bits_ = 0;
  int pos_ = 0;
};

}  // namespace texproc::bptc
