// The BC1 block as the block-by-block encoder and the image passes
// (bc1_passes.cpp) work on it: quantized endpoints, the palette the decoder
// makes of them (bc_decode.cpp's arithmetic), a scored candidate, and the
// bytes it is written as.
#pragma once

#include <cstdint>

namespace texproc::bc1 {

inline int expand5(int v) { return v << 3 | v >> 2; }
inline int expand6(int v) { return v << 2 | v >> 4; }

struct Endpoints {
  int c[2][3];  // quantized: 5, 6, 5 bits
};

// The decoder's palette: four colours, or three and black.
inline void palette(const Endpoints& e, bool four, int pal[4][3]) {
  for (int k = 0; k < 2; ++k) {
    pal[k][0] = expand5(e.c[k][0]);
    pal[k][1] = expand6(e.c[k][1]);
    pal[k][2] = expand5(e.c[k][2]);
  }
  for (int ch = 0; ch < 3; ++ch) {
    if (four) {
      pal[2][ch] = (2 * pal[0][ch] + pal[1][ch] + 1) / 3;
      pal[3][ch] = (pal[0][ch] + 2 * pal[1][ch] + 1) / 3;
    } else {
      pal[2][ch] = (pal[0][ch] + pal[1][ch] + 1) / 2;
      pal[3][ch] = 0;
    }
  }
}

struct Result {
  Endpoints e;
  bool four = true;
  std::uint8_t idx[16] = {};
  long long error = 0;
};

// The 8 bytes of a candidate: the endpoints ordered for its mode (c0 > c1:
// four colours; c0 <= c1: three), the indices remapped to match.
void write(const Result& r, std::uint8_t out[8]);

}  // namespace texproc::bc1
