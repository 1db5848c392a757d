// A BPTC block's 128 bits written from the lowest up (the order the
// decoders in bptc_decode.cpp read them), for the BC7 and BC6H packers.
#pragma once

#include <cstdint>

namespace texproc::bptc {

class BitWriter {
 public:
  void write(std::uint32_t v, int n) {  // n <= 32 bits, v < 2^n
    const std::uint64_t bits = std::uint64_t(v);
    if (pos_ < 64) {
      lo_ |= bits << pos_;
      if (pos_ + n > 64) hi_ |= bits >> (64 - pos_);
    } else {
      hi_ |= bits << (pos_ - 64);
    }
    pos_ += n;
  }
  int position() const { return pos_; }
  void store(std::uint8_t out[16]) const {
    for (int i = 0; i < 8; ++i) out[i] = std::uint8_t(lo_ >> (8 * i)), out[8 + i] = std::uint8_t(hi_ >> (8 * i));
  }

 private:
  std::uint64_t lo_ = 0, hi_ = 0;
  int pos_ = 0;
};

}  // namespace texproc::bptc
