// Colour under fully transparent texels: left alone, zeroed, or bled outward
// from the visible texels, so that a GPU's bilinear filtering of a
// straight-alpha texture (BC1 with alpha, BC2, BC3) blends edges towards
// the visible colour instead of towards whatever the artist left there
// (often black: dark fringes).
#include <algorithm>
#include <array>
#include <cstring>
#include <string_view>
#include <vector>

#include "texproc/error.h"
#include "texproc/image.h"
#include "texproc/transparent_color.h"

namespace texproc {

TransparentColor parse_transparent_color(std::string_view n) {
  if (n == "keep") return TransparentColor::keep;
  if (n == "bleed") return TransparentColor::bleed;
  if (n == "zero") return TransparentColor::zero;
  throw Error(ErrorCode::bad_arguments,
              "unknown --transparent-color '" + std::string(n) + "' (valid: keep, bleed, zero)");
}

void apply_transparent_color(Image& img, TransparentColor policy) {
  if (policy == TransparentColor::keep || img.channels() != 4 || img.type() != PixelType::u8) return;
  const int W = img.width(), H = img.height();
  auto px = [&](int x, int y) { return img.row<std::uint8_t>(y) + 4 * x; };
  if (policy == TransparentColor::zero) {
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        if (px(x, y)[3] == 0) std::memset(px(x, y), 0, 3);
    return;
  }
  // Bleed: rings of dilation. Each pass gives every still-empty transparent
  // texel the average colour of its already-filled 8-neighbours, reading
  // the previous pass only (deterministic, independent of scan order).
  std::vector<std::uint8_t> filled(std::size_t(W) * H);
  std::size_t empty = 0;
  long long sum[3] = {};
  long long opaque = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const bool visible = px(x, y)[3] != 0;
      filled[std::size_t(y) * W + x] = visible;
      if (!visible) {
        ++empty;
      } else {
        for (int c = 0; c < 3; ++c) sum[c] += px(x, y)[c];
        ++opaque;
      }
    }
  if (opaque == 0) return;  // nothing visible to bleed from
  std::vector<std::uint8_t> next;
  std::vector<std::array<std::uint8_t, 3>> colour;
  for (int pass = 0; pass < 64 && empty > 0; ++pass) {
    next = filled;
    std::vector<std::pair<std::size_t, std::array<std::uint8_t, 3>>> updates;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = std::size_t(y) * W + x;
        if (filled[i]) continue;
        int acc[3] = {}, n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= W || ny >= H) continue;
            if (!filled[std::size_t(ny) * W + nx]) continue;
            for (int c = 0; c < 3; ++c) acc[c] += px(nx, ny)[c];
            ++n;
          }
        if (n == 0) continue;
        updates.push_back({i,
                           {std::uint8_t((acc[0] + n / 2) / n), std::uint8_t((acc[1] + n / 2) / n),
                            std::uint8_t((acc[2] + n / 2) / n)}});
        next[i] = 1;
      }
    for (const auto& [i, rgb] : updates) {
      std::memcpy(px(int(i % W), int(i / W)), rgb.data(), 3);
      --empty;
    }
    filled.swap(next);
  }
  // Texels farther than 64 rings from any visible one take the mean colour.
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (!filled[std::size_t(y) * W + x]) {
        for (int c = 0; c < 3; ++c) px(x, y)[c] = std::uint8_t((sum[c] + opaque / 2) / opaque);
      }
}

}  // namespace texproc
