// The scalar reference of value_palette.h (namespace ref): what value_palette_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "block/value_palette.h"

namespace texproc::ref {
void value_palette_nearest(const double t[16], const double pal[8], std::uint8_t codes[16], double errors[16]) {
  for (int i = 0; i < 16; ++i) {
    int best = 0;
    double be = (t[i] - pal[0]) * (t[i] - pal[0]);
    for (int k = 1; k < 8; ++k) {
      const double e = (t[i] - pal[k]) * (t[i] - pal[k]);
      if (e < be) {
        be = e;
        best = k;
      }
    }
    codes[i] = std::uint8_t(best);
    errors[i] = be;
  }
}
}  // namespace texproc::ref
