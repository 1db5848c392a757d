// BC7 and BC6H decoding: blocks built by hand from the specification's
// layout with the texels worked out from its equations, every mode; and
// Pillow (python3-pil 9.4, an independent decoder) on random blocks of every
// mode and partition.
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "support/images.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/texture.h"

namespace fs = std::filesystem;
using namespace texproc;
using texproc::test::slurp_file;

namespace {

// Builds a 128-bit block from the lowest bit up, as the specification lays
// fields out.
struct BitWriter {
  std::uint8_t b[16] = {};
  int pos = 0;
  void put(std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i, ++pos)
      if (v >> i & 1) b[pos / 8] = std::uint8_t(b[pos / 8] | 1 << (pos % 8));
  }
};

std::array<std::array<std::uint8_t, 4>, 16> bc7(const std::uint8_t* block) {
  float f[16][4];
  decode_block(TexelFormat::bc7_unorm, block, f);
  std::array<std::array<std::uint8_t, 4>, 16> out{};
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) out[i][c] = std::uint8_t(std::lround(f[i][c] * 255.0f));
  return out;
}

int expand(int v, int n) { return (v << (8 - n) | v >> (2 * n - 8)) & 255; }
int lerp(int a, int b, int w) { return ((64 - w) * a + w * b + 32) >> 6; }

}  // namespace

// Mode 6 (one subset, 7-bit RGBA + per-endpoint p-bits, 4-bit indices): the
// texels at indices 0, 15 and between them, worked out from the equations.
TEST(Bc7Decode, Mode6ByHand) {
  BitWriter w;
  w.put(1u << 6, 7);  // mode 6
  const int e[2][4] = {{10, 100, 50, 127}, {120, 3, 77, 20}};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 2; ++k) w.put(std::uint32_t(e[k][c]), 7);
  const int p[2] = {1, 0};
  w.put(std::uint32_t(p[0]), 1);
  w.put(std::uint32_t(p[1]), 1);
  int idx[16];
  for (int i = 0; i < 16; ++i) idx[i] = (i * 7) % 16;
  idx[0] = 5;  // the anchor: 3 bits (its top bit 0)
  for (int i = 0; i < 16; ++i) w.put(std::uint32_t(idx[i]), i == 0 ? 3 : 4);
  ASSERT_EQ(w.pos, 128);
  static const int kW4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
  const auto px = bc7(w.b);
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) {
      const int a = expand(e[0][c] << 1 | p[0], 8), b = expand(e[1][c] << 1 | p[1], 8);
      EXPECT_EQ(px[i][c], lerp(a, b, kW4[idx[i]])) << "texel " << i << " channel " << c;
    }
}

// Mode 4 (rotation, index selection): 5-bit colour, 6-bit alpha, 2- and
// 3-bit index sets; with the selection bit the colour takes the 3-bit set;
// rotation 1 swaps red and alpha after interpolation.
TEST(Bc7Decode, Mode4RotationAndIndexSelectionByHand) {
  for (int rotation = 0; rotation < 4; ++rotation)
    for (int isb = 0; isb < 2; ++isb) {
      BitWriter w;
      w.put(1u << 4, 5);
      w.put(std::uint32_t(rotation), 2);
      w.put(std::uint32_t(isb), 1);
      const int col[2][3] = {{3, 30, 17}, {28, 1, 9}}, alpha[2] = {60, 5};
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 2; ++k) w.put(std::uint32_t(col[k][c]), 5);
      for (int k = 0; k < 2; ++k) w.put(std::uint32_t(alpha[k]), 6);
      int i2[16], i3[16];
      for (int i = 0; i < 16; ++i) {
        i2[i] = (i * 3) % 4;
        i3[i] = (i * 5) % 8;
      }
      i2[0] = 1;
      i3[0] = 2;  // anchors one bit shorter
      for (int i = 0; i < 16; ++i) w.put(std::uint32_t(i2[i]), i == 0 ? 1 : 2);
      for (int i = 0; i < 16; ++i) w.put(std::uint32_t(i3[i]), i == 0 ? 2 : 3);
      ASSERT_EQ(w.pos, 128);
      static const int kW2[4] = {0, 21, 43, 64}, kW3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
      const auto px = bc7(w.b);
      for (int i = 0; i < 16; ++i) {
        int v[4];
        for (int c = 0; c < 3; ++c)
          v[c] = lerp(expand(col[0][c], 5), expand(col[1][c], 5), isb ? kW3[i3[i]] : kW2[i2[i]]);
        v[3] = lerp(expand(alpha[0], 6), expand(alpha[1], 6), isb ? kW2[i2[i]] : kW3[i3[i]]);
        if (rotation) std::swap(v[3], v[rotation - 1]);
        for (int c = 0; c < 4; ++c)
          EXPECT_EQ(px[i][c], v[c]) << "rotation " << rotation << " isb " << isb << " texel " << i << " c " << c;
      }
    }
}

// Mode 1 (two subsets, shared p-bits): partition 13 (rows 0-1 subset 0,
// rows 2-3 subset 1, anchor 15), every texel at its subset's endpoint 0 or 1;
// alpha 255.
TEST(Bc7Decode, Mode1PartitionsAndSharedPbitsByHand) {
  BitWriter w;
  w.put(1u << 1, 2);
  w.put(13, 6);
  const int e[2][2][3] = {{{1, 2, 3}, {60, 61, 62}}, {{33, 0, 63}, {7, 40, 20}}};  // subset, endpoint, channel
  for (int c = 0; c < 3; ++c)
    for (int s = 0; s < 2; ++s)
      for (int k = 0; k < 2; ++k) w.put(std::uint32_t(e[s][k][c]), 6);
  const int p[2] = {1, 0};
  w.put(std::uint32_t(p[0]), 1);
  w.put(std::uint32_t(p[1]), 1);
  // Indices 0 (endpoint 0) or 7 (endpoint 1); texel 0 and 15 are anchors (2 bits).
  int idx[16];
  for (int i = 0; i < 16; ++i) idx[i] = i % 3 == 0 ? 0 : 7;
  idx[0] = 0;
  idx[15] = 3;
  for (int i = 0; i < 16; ++i) w.put(std::uint32_t(idx[i]), i == 0 || i == 15 ? 2 : 3);
  ASSERT_EQ(w.pos, 128);
  static const int kW3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
  const auto px = bc7(w.b);
  for (int i = 0; i < 16; ++i) {
    const int s = i >= 8 ? 1 : 0;
    for (int c = 0; c < 3; ++c) {
      const int a = expand(e[s][0][c] << 1 | p[s], 7), b = expand(e[s][1][c] << 1 | p[s], 7);
      EXPECT_EQ(px[i][c], lerp(a, b, kW3[idx[i]])) << "texel " << i;
    }
    EXPECT_EQ(px[i][3], 255);
  }
}

TEST(Bc7Decode, ReservedModeIsZero) {
  std::uint8_t b[16] = {};
  b[5] = 0xFF;
  for (const auto& t : bc7(b))
    for (int c = 0; c < 4; ++c) EXPECT_EQ(t[c], 0);
}

// BC6H mode 3 (one subset, 10-bit endpoints, untransformed) and mode 15
// (transformed, 16-bit base with its top six bits stored reversed, 4-bit
// deltas), unsigned and signed, worked out from the specification's
// unquantization, interpolation and final scaling.
TEST(Bc6hDecode, Modes3And15ByHand) {
  auto unq_u = [](int x, int bits) {
    if (bits >= 15) return x;
    if (x == 0) return 0;
    if (x == (1 << bits) - 1) return 0xFFFF;
    return ((x << 15) + 0x4000) >> (bits - 1);
  };
  static const int kW4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
  int idx[16];
  for (int i = 0; i < 16; ++i) idx[i] = (i * 11) % 16;
  idx[0] = 6;
  {  // mode 3, unsigned
    BitWriter w;
    w.put(3, 5);
    const int e[2][3] = {{100, 500, 900}, {1023, 0, 321}};
    for (int k = 0; k < 2; ++k)
      for (int c = 0; c < 3; ++c) w.put(std::uint32_t(e[k][c]), 10);
    for (int i = 0; i < 16; ++i) w.put(std::uint32_t(idx[i]), i == 0 ? 3 : 4);
    ASSERT_EQ(w.pos, 128);
    float f[16][4];
    decode_block(TexelFormat::bc6h_ufloat, w.b, f);
    for (int i = 0; i < 16; ++i) {
      for (int c = 0; c < 3; ++c) {
        const int v = lerp(unq_u(e[0][c], 10), unq_u(e[1][c], 10), kW4[idx[i]]);
        Imath::half h;
        h.setBits(std::uint16_t((v * 31) >> 6));
        EXPECT_EQ(f[i][c], float(h)) << "texel " << i << " channel " << c;
      }
      EXPECT_EQ(f[i][3], 1.0f);
    }
  }
  {  // mode 15, signed: base 16 bits (r0[9:0] then r0[10:15] reversed), deltas 4 bits
    const int base[3] = {0x1234, -0x2000, 0x0F0F}, delta[3] = {7, -8, -1};
    BitWriter w;
    w.put(15, 5);
    for (int c = 0; c < 3; ++c) w.put(std::uint32_t(base[c]) & 1023, 10);
    for (int c = 0; c < 3; ++c) {
      w.put(std::uint32_t(delta[c]) & 15, 4);
      for (int bit = 15; bit >= 10; --bit) w.put(std::uint32_t(base[c]) >> bit & 1, 1);
    }
    for (int i = 0; i < 16; ++i) w.put(std::uint32_t(idx[i]), i == 0 ? 3 : 4);
    ASSERT_EQ(w.pos, 128);
    float f[16][4];
    decode_block(TexelFormat::bc6h_sfloat, w.b, f);
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 3; ++c) {
        // 16-bit endpoints are used as they are; e1 = e0 + delta (wrapped to 16 bits, signed).
        const int e0 = base[c], e1 = std::int16_t(std::uint16_t(base[c] + delta[c]));
        const int v = lerp(e0, e1, kW4[idx[i]]);
        const std::uint16_t bits = v < 0 ? std::uint16_t(0x8000 | ((-v * 31) >> 5)) : std::uint16_t((v * 31) >> 5);
        Imath::half h;
        h.setBits(bits);
        EXPECT_EQ(f[i][c], float(h)) << "texel " << i << " channel " << c;
      }
  }
}

TEST(Bc6hDecode, ReservedModesAreZero) {
  for (int mode : {19, 23, 27, 31}) {
    std::uint8_t b[16];
    std::memset(b, 0xA5, 16);
    b[0] = std::uint8_t((b[0] & ~31) | mode);
    float f[16][4];
    decode_block(TexelFormat::bc6h_ufloat, b, f);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(f[i][0] + f[i][1] + f[i][2], 0.0f) << mode;
  }
}

namespace {

// Random blocks of every mode: BC7 mode m's low byte ends in 1 << m (modes
// 0-7 in turn; the other bits random, so every partition and rotation
// appears); BC6H's modes by their 2- or 5-bit numbers in turn.
std::vector<std::uint8_t> random_blocks(bool bc6h, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint8_t> v(std::size_t(count) * 16);
  for (auto& b : v) b = std::uint8_t(rng());
  static const int kBc6hModes[14] = {0, 1, 2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15};
  for (int k = 0; k < count; ++k) {
    std::uint8_t& b0 = v[std::size_t(k) * 16];
    if (bc6h) {
      const int m = kBc6hModes[k % 14];
      b0 = std::uint8_t(m < 2 ? (b0 & ~3) | m : (b0 & ~31) | m);
    } else {
      const int m = k % 8;
      b0 = std::uint8_t((b0 & ~((2 << m) - 1)) | 1 << m);
    }
  }
  return v;
}

// Pillow's pixels for a DDS of `blocks` (w x h texels), as raw bytes.
std::string pillow_pixels(const std::string& dir, TexelFormat f, const std::vector<std::uint8_t>& blocks, int w,
                          int h) {
  Texture t;
  t.format = f;
  t.width = std::uint32_t(w);
  t.height = std::uint32_t(h);
  t.levels = t.layers = t.faces = 1;
  t.images = {blocks};
  write_texture(dir + "/b.dds", t);
  const std::string out = dir + "/px.bin";
  const std::string cmd = "/usr/bin/python3 -c \"from PIL import Image; im = Image.open('" + dir + "/b.dds'); open('" +
                          out + "', 'wb').write(im.mode.encode() + b' ' + im.tobytes())\" 2>" + dir + "/err.txt";
  if (std::system(cmd.c_str()) != 0) return "error: " + slurp_file(dir + "/err.txt");
  return slurp_file(out);
}

bool have_pillow() { return std::system("/usr/bin/python3 -c 'import PIL' >/dev/null 2>&1") == 0; }

}  // namespace

// 4096 random BC7 blocks, 512 of each mode: the same texels as Pillow's.
TEST(Bc7Decode, MatchesPillowOnRandomBlocksOfEveryMode) {
  if (!have_pillow()) GTEST_SKIP() << "python3-pil not installed";
  const std::string dir = (fs::temp_directory_path() / "texproc_bc7_pil").string();
  fs::create_directories(dir);
  const int bw = 64, bh = 64;
  const std::vector<std::uint8_t> blocks = random_blocks(false, bw * bh, 7);
  const std::string px = pillow_pixels(dir, TexelFormat::bc7_unorm, blocks, bw * 4, bh * 4);
  ASSERT_EQ(px.substr(0, 5), "RGBA ") << px.substr(0, 200);
  ASSERT_EQ(px.size(), 5 + std::size_t(bw * bh) * 64);
  int wrong = 0;
  for (int k = 0; k < bw * bh; ++k) {
    const auto t = bc7(&blocks[std::size_t(k) * 16]);
    for (int i = 0; i < 16; ++i) {
      const int x = (k % bw) * 4 + i % 4, y = (k / bw) * 4 + i / 4;
      for (int c = 0; c < 4; ++c) {
        const int theirs = std::uint8_t(px[5 + (std::size_t(y) * bw * 4 + x) * 4 + c]);
        if (theirs != t[i][c] && wrong++ < 5)
          ADD_FAILURE() << "block " << k << " (mode " << k % 8 << ") texel " << i << " channel " << c << ": "
                        << int(t[i][c]) << " vs Pillow " << theirs;
      }
    }
  }
  EXPECT_EQ(wrong, 0);
  fs::remove_all(dir);
}

// 4096 random BC6H blocks of the 14 modes, unsigned and signed: Pillow
// decodes to 8 bits (the half clamped to [0, 1]); texproc's halfs, clamped
// and scaled the same way, within one level. Signed blocks of the
// transformed modes with fewer than 16 endpoint bits are left out: Pillow
// 9.4 does not sign-extend an endpoint again after adding the delta to the
// base (wrapped to the endpoint bits), so it reads a negative endpoint as a
// large positive one; the specification's endpoints are two's-complement
// values of that many bits (Direct3D's reference decoder sign-extends there
// too). Bc6hDecode.SignedTransformedEndpointsByHand checks those modes.
TEST(Bc6hDecode, MatchesPillowOnRandomBlocksOfEveryMode) {
  if (!have_pillow()) GTEST_SKIP() << "python3-pil not installed";
  const std::string dir = (fs::temp_directory_path() / "texproc_bc6h_pil").string();
  fs::create_directories(dir);
  for (TexelFormat f : {TexelFormat::bc6h_ufloat, TexelFormat::bc6h_sfloat}) {
    const int bw = 64, bh = 64;
    const std::vector<std::uint8_t> blocks = random_blocks(true, bw * bh, f == TexelFormat::bc6h_ufloat ? 11 : 12);
    const std::string px = pillow_pixels(dir, f, blocks, bw * 4, bh * 4);
    ASSERT_EQ(px.substr(0, 4), "RGB ") << px.substr(0, 200);
    ASSERT_EQ(px.size(), 4 + std::size_t(bw * bh) * 48);
    int wrong = 0, inside = 0;
    int compared = 0;
    for (int k = 0; k < bw * bh; ++k) {
      static const int kModes[14] = {0, 1, 2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15};
      const int mode = kModes[k % 14];
      if (f == TexelFormat::bc6h_sfloat && mode != 3 && mode != 30 && mode != 15) continue;
      ++compared;
      float t[16][4];
      decode_block(f, &blocks[std::size_t(k) * 16], t);
      for (int i = 0; i < 16; ++i) {
        const int x = (k % bw) * 4 + i % 4, y = (k / bw) * 4 + i / 4;
        for (int c = 0; c < 3; ++c) {
          const float v =
              std::isfinite(t[i][c]) ? std::min(std::max(t[i][c], 0.0f), 1.0f) : (t[i][c] > 0 ? 1.0f : 0.0f);
          const int mine = int(std::lround(v * 255.0f)),
                    theirs = std::uint8_t(px[4 + (std::size_t(y) * bw * 4 + x) * 3 + c]);
          if (v > 0.0f && v < 1.0f) ++inside;
          if (std::abs(mine - theirs) > 1 && wrong++ < 5)
            ADD_FAILURE() << format_info(f).name << " block " << k << " texel " << i << " channel " << c << ": "
                          << t[i][c] << " vs Pillow " << theirs;
        }
      }
    }
    EXPECT_EQ(wrong, 0) << "of " << compared << " blocks";
    EXPECT_GT(inside, 2000) << "too few texels inside (0, 1) to compare";
  }
  fs::remove_all(dir);
}

// BC6H mode 2, signed (two subsets, 11-bit base, deltas of 5/4/4 bits): a
// base of -16 and deltas that keep every endpoint negative; the endpoints,
// wrapped to 11 bits, are 11-bit two's-complement values (-14, ...), not the
// large positive numbers Pillow 9.4 reads there.
TEST(Bc6hDecode, SignedTransformedEndpointsByHand) {
  // The extension's Table.F for mode 2, field by field: (variable, high bit, low bit).
  struct Seg {
    const char* v;
    int hi, lo;
  };
  static const Seg kMode2[] = {{"r0", 9, 0}, {"g0", 9, 0},   {"b0", 9, 0}, {"r1", 4, 0}, {"r0", 10, 10}, {"g2", 3, 0},
                               {"g1", 3, 0}, {"g0", 10, 10}, {"b3", 0, 0}, {"g3", 3, 0}, {"b1", 3, 0},   {"b0", 10, 10},
                               {"b3", 1, 1}, {"b2", 3, 0},   {"r2", 4, 0}, {"b3", 2, 2}, {"r3", 4, 0},   {"b3", 3, 3}};
  // Endpoint values: e0 11-bit, the others deltas (r 5 bits, g and b 4 bits), two's complement.
  const int e0[3] = {-16, -300, -1000};
  const int d[3][3] = {{2, -3, 7}, {-1, 5, -8}, {-16, 0, 1}};  // e1, e2, e3 deltas by channel
  auto value = [&](const std::string& v) {
    const int ch = v[0] == 'r' ? 0 : v[0] == 'g' ? 1 : 2, e = v[1] - '0';
    return e == 0 ? e0[ch] : d[e - 1][ch];
  };
  BitWriter w;
  w.put(2, 5);
  for (const Seg& s : kMode2) {
    const int x = value(s.v);
    for (int bit = s.lo; bit <= s.hi; ++bit) w.put(std::uint32_t(x) >> bit & 1, 1);
  }
  const int partition = 13;  // rows 0-1: subset 0, rows 2-3: subset 1 (anchor texel 15)
  w.put(partition, 5);
  int idx[16];
  for (int i = 0; i < 16; ++i) idx[i] = (i * 5) % 8;
  idx[0] = 2;
  idx[15] = 3;
  for (int i = 0; i < 16; ++i) w.put(std::uint32_t(idx[i]), i == 0 || i == 15 ? 2 : 3);
  ASSERT_EQ(w.pos, 128);
  auto unq_s = [](int x, int bits) {
    const bool neg = x < 0;
    if (neg) x = -x;
    int u = x == 0 ? 0 : x >= (1 << (bits - 1)) - 1 ? 0x7FFF : ((x << 15) + 0x4000) >> (bits - 1);
    return neg ? -u : u;
  };
  auto wrap11 = [](int v) {
    v &= 2047;
    return v >= 1024 ? v - 2048 : v;
  };
  static const int kW3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
  float f[16][4];
  decode_block(TexelFormat::bc6h_sfloat, w.b, f);
  for (int i = 0; i < 16; ++i) {
    const int s = i >= 8 ? 1 : 0;
    for (int c = 0; c < 3; ++c) {
      const int a = s == 0 ? e0[c] : wrap11(e0[c] + d[1][c]);
      const int b = wrap11(e0[c] + d[s == 0 ? 0 : 2][c]);
      const int v = lerp(unq_s(a, 11), unq_s(b, 11), kW3[idx[i]]);
      const std::uint16_t bits = v < 0 ? std::uint16_t(0x8000 | ((-v * 31) >> 5)) : std::uint16_t((v * 31) >> 5);
      Imath::half h;
      h.setBits(bits);
      EXPECT_EQ(f[i][c], float(h)) << "texel " << i << " channel " << c;
      EXPECT_LT(f[i][c], 0.0f);
    }
  }
}

// DDS (DX10 header: DXGI 95, 96, 98, 99), KTX2 (VkFormat 143-146, libktx's
// descriptors) and KTX1 (GL 0x8E8C-0x8E8F) hold BC6H and BC7 and give back
// the same blocks; decompressing picks floats for BC6H.
TEST(BptcContainers, RoundTripEveryContainer) {
  const std::string dir = (fs::temp_directory_path() / "texproc_bptc_containers").string();
  fs::create_directories(dir);
  for (TexelFormat f :
       {TexelFormat::bc6h_ufloat, TexelFormat::bc6h_sfloat, TexelFormat::bc7_unorm, TexelFormat::bc7_srgb}) {
    Texture t;
    t.format = f;
    t.width = 9;
    t.height = 6;
    t.levels = 2;
    t.layers = t.faces = 1;
    t.images = {random_blocks(f != TexelFormat::bc7_unorm && f != TexelFormat::bc7_srgb, 6, 3),
                random_blocks(false, 1, 4)};
    for (const char* ext : {".dds", ".ktx2", ".ktx"}) {
      const std::string p = dir + "/t" + ext;
      write_texture(p, t);
      const Texture back = read_texture(p);
      EXPECT_EQ(back.format, f) << ext;
      EXPECT_EQ(back.width, 9u);
      EXPECT_EQ(back.levels, 2u);
      EXPECT_EQ(back.images, t.images) << format_info(f).name << ext;
    }
    const Image img = decode_texture_image(t, 0, 0, 0, format_info(f).is_float ? PixelType::f32 : PixelType::u8);
    EXPECT_EQ(img.channels(), f == TexelFormat::bc7_unorm || f == TexelFormat::bc7_srgb ? 4 : 3);
  }
  fs::remove_all(dir);
}
