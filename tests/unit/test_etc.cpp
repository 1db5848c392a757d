// ETC1, ETC2 and EAC decoding: hand-built blocks with texels worked out from
// the specification's equations, a second decoder written plainly from the
// specification's bit tables (fields as lists of bit positions) compared on
// random bit patterns, and android-libetc1's decoder for ETC1.
#include <gtest/gtest.h>

#include <etc1.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "etc/etc_tables.h"
#include "support/blocks.h"
#include "support/images.h"
#include "support/targets.h"
#include "support/threads.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/runtime.h"
#include "texproc/texture.h"

using namespace texproc;
using namespace texproc::test;

namespace {

// A block as 64 bits numbered as in the specification (63 = top bit of byte 0).
struct Bits {
  std::uint64_t v = 0;
  int get(std::initializer_list<int> positions) const {
    int r = 0;
    for (int p : positions) r = r << 1 | int(v >> p & 1);
    return r;
  }
  int range(int high, int low) const {
    int r = 0;
    for (int p = high; p >= low; --p) r = r << 1 | int(v >> p & 1);
    return r;
  }
  void put(int high, int count, std::uint64_t value) {
    for (int i = 0; i < count; ++i) {
      const int p = high - count + 1 + i;
      v = (v & ~(std::uint64_t(1) << p)) | ((value >> i & 1) << p);
    }
  }
  std::vector<std::uint8_t> bytes() const {
    std::vector<std::uint8_t> b(8);
    for (int i = 0; i < 8; ++i) b[i] = std::uint8_t(v >> (56 - 8 * i));
    return b;
  }
  static Bits of(const std::uint8_t* b) {
    Bits r;
    for (int i = 0; i < 8; ++i) r.v = r.v << 8 | b[i];
    return r;
  }
};

int clamp8(int v) { return v < 0 ? 0 : v > 255 ? 255 : v; }
int sext3(int v) { return v & 4 ? v - 8 : v; }
int ext(int v, int bits) { return (v << (8 - bits)) | (v >> (2 * bits - 8)); }

// Texel (x, y)'s 2-bit index: MSB in bits 16..31, LSB in 0..15, at x * 4 + y.
int index2(const Bits& b, int x, int y) { return b.get({x * 4 + y + 16, x * 4 + y}); }

const int kTables[8][2] = {{2, 8}, {5, 17}, {9, 29}, {13, 42}, {18, 60}, {24, 80}, {33, 106}, {47, 183}};
const int kDist[8] = {3, 6, 11, 16, 23, 32, 41, 64};
const int kEac[16][4] = {{2, 5, 8, 14}, {2, 6, 9, 12}, {1, 4, 7, 12}, {1, 3, 5, 12}, {2, 5, 7, 11}, {2, 6, 8, 10},
                         {3, 6, 7, 10}, {2, 4, 7, 10}, {1, 5, 7, 9},  {1, 4, 7, 9},  {1, 3, 7, 9},  {1, 4, 6, 9},
                         {2, 3, 6, 9},  {0, 1, 2, 9},  {3, 5, 7, 8},  {2, 4, 6, 8}};
// EAC modifier for index i (0..7): indices 0-3 are -(table[3 - i] + 1)... as
// the specification lists them: negative values for 0..3, positive for 4..7.
int eac_modifier(int table, int i) {
  static const int neg[16][4] = {{-3, -6, -9, -15}, {-3, -7, -10, -13}, {-2, -5, -8, -13}, {-2, -4, -6, -13},
                                 {-3, -6, -8, -12}, {-3, -7, -9, -11},  {-4, -7, -8, -11}, {-3, -5, -8, -11},
                                 {-2, -6, -8, -10}, {-2, -5, -8, -10},  {-2, -4, -8, -10}, {-2, -5, -7, -10},
                                 {-3, -4, -7, -10}, {-1, -2, -3, -10},  {-4, -6, -8, -9},  {-3, -5, -7, -9}};
  return i < 4 ? neg[table][i] : kEac[table][i - 4];
}

struct Px {
  int r, g, b, a;
};

// The reference: ETC2 RGB / punch-through, plainly from the tables.
std::vector<Px> plain_etc2(const Bits& b, bool punch, bool etc1_only = false) {
  std::vector<Px> out(16);
  const bool opaque = punch ? b.get({33}) : true;
  const bool diff = punch ? true : b.get({33});
  auto sub_blocks = [&](int c1[3], int c2[3]) {
    const int t1 = b.range(39, 37), t2 = b.range(36, 34);
    const bool flip = b.get({32});
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const bool second = flip ? y >= 2 : x >= 2;
        const int* c = second ? c2 : c1;
        const int t = second ? t2 : t1;
        const int i = index2(b, x, y);
        int m = i == 0 ? kTables[t][0] : i == 1 ? kTables[t][1] : i == 2 ? -kTables[t][0] : -kTables[t][1];
        if (!opaque && (i == 0 || i == 2)) m = 0;
        Px p{clamp8(c[0] + m), clamp8(c[1] + m), clamp8(c[2] + m), 255};
        if (!opaque && i == 2) p = {0, 0, 0, 0};
        out[y * 4 + x] = p;
      }
  };
  if (!diff) {
    int c1[3] = {ext(b.range(63, 60), 4), ext(b.range(55, 52), 4), ext(b.range(47, 44), 4)};
    int c2[3] = {ext(b.range(59, 56), 4), ext(b.range(51, 48), 4), ext(b.range(43, 40), 4)};
    sub_blocks(c1, c2);
    return out;
  }
  const int R = b.range(63, 59), G = b.range(55, 51), B = b.range(47, 43);
  const int R2 = R + sext3(b.range(58, 56)), G2 = G + sext3(b.range(50, 48)), B2 = B + sext3(b.range(42, 40));
  auto paint = [&](const int p[4][3]) {
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const int i = index2(b, x, y);
        out[y * 4 + x] =
            !opaque && i == 2 ? Px{0, 0, 0, 0} : Px{clamp8(p[i][0]), clamp8(p[i][1]), clamp8(p[i][2]), 255};
      }
  };
  if (etc1_only || (R2 >= 0 && R2 <= 31 && G2 >= 0 && G2 <= 31 && B2 >= 0 && B2 <= 31)) {
    int c1[3] = {ext(R, 5), ext(G, 5), ext(B, 5)};
    int c2[3] = {ext(R2 & 31, 5), ext(G2 & 31, 5), ext(B2 & 31, 5)};
    sub_blocks(c1, c2);
  } else if (R2 < 0 || R2 > 31) {  // T
    const int c1[3] = {ext(b.get({60, 59, 57, 56}), 4), ext(b.range(55, 52), 4), ext(b.range(51, 48), 4)};
    const int c2[3] = {ext(b.range(47, 44), 4), ext(b.range(43, 40), 4), ext(b.range(39, 36), 4)};
    const int d = kDist[b.get({35, 34, 32})];
    const int p[4][3] = {{c1[0], c1[1], c1[2]},
                         {c2[0] + d, c2[1] + d, c2[2] + d},
                         {c2[0], c2[1], c2[2]},
                         {c2[0] - d, c2[1] - d, c2[2] - d}};
    paint(p);
  } else if (G2 < 0 || G2 > 31) {  // H
    const int r1 = b.range(62, 59), g1 = b.get({58, 57, 56, 52}), b1 = b.get({51, 49, 48, 47});
    const int r2 = b.range(46, 43), g2 = b.get({42, 41, 40, 39}), b2 = b.range(38, 35);
    const int d = kDist[b.get({34, 32}) * 2 + ((r1 * 256 + g1 * 16 + b1) >= (r2 * 256 + g2 * 16 + b2))];
    const int c1[3] = {ext(r1, 4), ext(g1, 4), ext(b1, 4)}, c2[3] = {ext(r2, 4), ext(g2, 4), ext(b2, 4)};
    const int p[4][3] = {{c1[0] + d, c1[1] + d, c1[2] + d},
                         {c1[0] - d, c1[1] - d, c1[2] - d},
                         {c2[0] + d, c2[1] + d, c2[2] + d},
                         {c2[0] - d, c2[1] - d, c2[2] - d}};
    paint(p);
  } else {  // planar
    const int o[3] = {ext(b.range(62, 57), 6), ext(b.get({56, 54, 53, 52, 51, 50, 49}), 7),
                      ext(b.get({48, 44, 43, 41, 40, 39}), 6)};
    const int h[3] = {ext(b.get({38, 37, 36, 35, 34, 32}), 6), ext(b.range(31, 25), 7), ext(b.range(24, 19), 6)};
    const int v[3] = {ext(b.range(18, 13), 6), ext(b.range(12, 6), 7), ext(b.range(5, 0), 6)};
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        int c[3];
        for (int k = 0; k < 3; ++k) {
          // R(x, y) = (x (RH - RO) + y (RV - RO) + 4 RO + 2) / 4, rounded down.
          const int n = x * (h[k] - o[k]) + y * (v[k] - o[k]) + 4 * o[k] + 2;
          c[k] = clamp8(n >= 0 ? n / 4 : -((-n + 3) / 4));
        }
        out[y * 4 + x] = {c[0], c[1], c[2], 255};
      }
  }
  return out;
}

// EAC, plainly: 11-bit (unsigned 0..2047, signed -1023..1023) or 8-bit.
std::vector<int> plain_eac(const Bits& b, int kind /* 0: 8-bit, 1: unsigned 11, 2: signed 11 */) {
  std::vector<int> out(16);
  int base = b.range(63, 56);
  const int mult = b.range(55, 52), table = b.range(51, 48);
  if (kind == 2) {
    if (base > 127) base -= 256;
    if (base == -128) base = -127;
  }
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) {
      const int k = x * 4 + y;  // column by column from bit 47 down
      const int m = eac_modifier(table, b.range(47 - 3 * k, 45 - 3 * k));
      int v;
      if (kind == 0) {
        v = clamp8(base + m * mult);
      } else if (kind == 1) {
        v = std::clamp(base * 8 + 4 + (mult ? m * mult * 8 : m), 0, 2047);
      } else {
        v = std::clamp(base * 8 + (mult ? m * mult * 8 : m), -1023, 1023);
      }
      out[y * 4 + x] = v;
    }
  return out;
}

void decode(TexelFormat f, const std::vector<std::uint8_t>& block, float t[16][4]) { decode_block(f, block.data(), t); }

void expect_rgba(TexelFormat f, const std::vector<std::uint8_t>& block, const std::vector<Px>& want, const char* what) {
  float t[16][4];
  decode(f, block, t);
  for (int i = 0; i < 16; ++i) {
    const int got[4] = {int(std::lround(t[i][0] * 255)), int(std::lround(t[i][1] * 255)),
                        int(std::lround(t[i][2] * 255)), int(std::lround(t[i][3] * 255))};
    ASSERT_EQ(got[0], want[i].r) << what << " texel " << i;
    ASSERT_EQ(got[1], want[i].g) << what << " texel " << i;
    ASSERT_EQ(got[2], want[i].b) << what << " texel " << i;
    ASSERT_EQ(got[3], want[i].a) << what << " texel " << i;
  }
}

}  // namespace

// Individual mode, worked by hand: base colours (0xAA, 0x33, 0x00) and
// (0x55, 0xCC, 0x00), tables 1 (+-5, +-17) and 6 (+-33, +-106), side by
// side; every index 0 (+a) but texel (1, 2), index 3 (-b).
TEST(EtcDecode, IndividualModeByHand) {
  Bits b;
  b.put(63, 4, 0xA);
  b.put(59, 4, 0x5);
  b.put(55, 4, 0x3);
  b.put(51, 4, 0xC);
  b.put(47, 4, 0);
  b.put(43, 4, 0);
  b.put(39, 3, 1);
  b.put(36, 3, 6);
  b.put(33, 1, 0);
  b.put(32, 1, 0);
  b.put(1 * 4 + 2 + 16, 1, 1);
  b.put(1 * 4 + 2, 1, 1);
  std::vector<Px> want(16);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      want[y * 4 + x] = x < 2 ? Px{0xAA + 5, 0x33 + 5, 5, 255} : Px{0x55 + 33, 0xCC + 33, 33, 255};
    }
  want[2 * 4 + 1] = {0xAA - 17, 0x33 - 17, 0, 255};
  for (TexelFormat f : {TexelFormat::etc1_rgb, TexelFormat::etc2_rgb_unorm})
    expect_rgba(f, b.bytes(), want, "individual");
}

// Differential mode, flipped (4x2 halves): base 5-bit (31, 0, 16) and delta
// (-3, +3, 0): second colour (28, 3, 16); table 7 (+-47, +-183) on top and
// table 0 (+-2, +-8) below, every index 1 (+b): clamping at 255 and 0.
TEST(EtcDecode, DifferentialModeByHand) {
  Bits b;
  b.put(63, 5, 31);
  b.put(58, 3, 5 /* -3 */);
  b.put(55, 5, 0);
  b.put(50, 3, 3);
  b.put(47, 5, 16);
  b.put(42, 3, 0);
  b.put(39, 3, 7);
  b.put(36, 3, 0);
  b.put(33, 1, 1);
  b.put(32, 1, 1);
  b.put(15, 16, 0xFFFF);  // LSBs 1, MSBs 0: index 1 everywhere
  auto e5 = [](int v) { return v << 3 | v >> 2; };
  std::vector<Px> want(16);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      want[y * 4 + x] =
          y < 2 ? Px{255, clamp8(e5(0) + 183), clamp8(e5(16) + 183), 255} : Px{e5(28) + 8, e5(3) + 8, e5(16) + 8, 255};
    }
  for (TexelFormat f : {TexelFormat::etc1_rgb, TexelFormat::etc2_rgb_unorm})
    expect_rgba(f, b.bytes(), want, "differential");
}

// T mode: red overflows. C1 = (0xF, 0x8, 0x0) by nibbles, C2 = (0x4, 0x0, 0x2),
// distance index 2 (11): paint colours C1, C2 + 11, C2, C2 - 11; texel
// (x, y) takes index (x + y) % 4.
TEST(EtcDecode, TModeByHand) {
  Bits b;
  b.put(60, 2, 3);
  b.put(57, 2, 3);  // R1 = 0xF: R1a + R1b > 3, so R = 28.. with dR >= 0 overflows
  b.put(63, 3, 7);
  b.put(58, 1, 0);
  b.put(55, 4, 0x8);
  b.put(51, 4, 0x0);
  b.put(47, 4, 0x4);
  b.put(43, 4, 0x0);
  b.put(39, 4, 0x2);
  b.put(35, 2, 1);
  b.put(32, 1, 0);
  b.put(33, 1, 1);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) {
      const int i = (x + y) % 4;
      b.put(x * 4 + y + 16, 1, i >> 1);
      b.put(x * 4 + y, 1, i & 1);
    }
  const Px paint[4] = {
      {0xFF, 0x88, 0x00, 255}, {0x44 + 11, 11, 0x22 + 11, 255}, {0x44, 0, 0x22, 255}, {0x44 - 11, 0, 0x22 - 11, 255}};
  std::vector<Px> want(16);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) want[y * 4 + x] = paint[(x + y) % 4];
  expect_rgba(TexelFormat::etc2_rgb_unorm, b.bytes(), want, "T");
  // With punch-through and the opaque bit clear, index 2 is transparent black.
  b.put(33, 1, 0);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      if ((x + y) % 4 == 2) want[y * 4 + x] = {0, 0, 0, 0};
  expect_rgba(TexelFormat::etc2_rgba1_unorm, b.bytes(), want, "T punch-through");
}

// H mode: green overflows. C1 = (0x1, 0x2, 0xF), C2 = (0x9, 0x8, 0x7) by
// nibbles: C1 < C2, so the distance index's low bit is 0; da = 1, db = 1:
// index 0b110 = 6, distance 41. Paint: C1 + 41, C1 - 41, C2 + 41, C2 - 41.
TEST(EtcDecode, HModeByHand) {
  Bits b;
  // R1 = 1 (62-59); G1 = 2: G1a = 1 (58-56), G1b = 0 (52); B1 = 15: B1a = 1 (51), B1b = 3 (49-48), B1c = 1 (47).
  b.put(62, 4, 1);
  b.put(58, 3, 1);
  b.put(52, 1, 0);
  b.put(51, 1, 1);
  b.put(49, 2, 3);
  b.put(47, 1, 1);
  // R2 = 9 (46-43), G2 = 8: G2a = 4 (42-40), G2b = 0 (39); B2 = 7 (38-35).
  b.put(46, 4, 9);
  b.put(42, 3, 4);
  b.put(39, 1, 0);
  b.put(38, 4, 7);
  b.put(34, 1, 1);
  b.put(32, 1, 1);
  b.put(33, 1, 1);
  // The mode: R = (bit 63 = 0, R1) = 1 plus dR = G1a = +1 stays in range; G = (bits 55-53 = 111, G1b,
  // B1a) = 29 plus dG = (bit 50 = 0, B1b) = +3 is 32: out of range.
  b.put(63, 1, 0);
  b.put(55, 3, 7);
  b.put(50, 1, 0);
  const int c1[3] = {0x11, 0x22, 0xFF}, c2[3] = {0x99, 0x88, 0x77};
  ASSERT_LT(1 * 256 + 2 * 16 + 15, 9 * 256 + 8 * 16 + 7);
  const int d = kDist[6];
  const Px paint[4] = {{c1[0] + d, c1[1] + d, 255, 255},
                       {0, 0, c1[2] - d, 255},
                       {c2[0] + d, c2[1] + d, c2[2] + d, 255},
                       {c2[0] - d, c2[1] - d, c2[2] - d, 255}};
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) {
      const int i = (x * 3 + y) % 4;
      b.put(x * 4 + y + 16, 1, i >> 1);
      b.put(x * 4 + y, 1, i & 1);
    }
  std::vector<Px> want(16);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) want[y * 4 + x] = paint[(x * 3 + y) % 4];
  expect_rgba(TexelFormat::etc2_rgb_unorm, b.bytes(), want, "H");
  // Swapping the colours flips the order bit: distance index 7 (64).
  Bits s = b;
  s.put(62, 4, 9);
  s.put(46, 4, 1);
  const Bits plain = s;
  const auto got = plain_etc2(plain, false);
  EXPECT_EQ(got[0].r, clamp8(0x99 + 64));
}

// Planar: blue overflows. O = (0x20, 0x40, 0x10) (6/7/6-bit), H = (0x3F, 0, 0x20),
// V = (0, 0x7F, 0x3F); texels from (x (H - O) + y (V - O) + 4 O + 2) >> 2.
TEST(EtcDecode, PlanarModeByHand) {
  const int RO = 0x20, GO = 0x40, BO = 0x10, RH = 0x3F, GH = 0, BH = 0x20, RV = 0, GV = 0x7F, BV = 0x3F;
  Bits b;
  b.put(62, 6, RO);
  b.put(56, 1, GO >> 6);
  b.put(54, 6, GO & 63);
  b.put(48, 1, BO >> 5);
  b.put(44, 2, BO >> 3 & 3);
  b.put(41, 2, BO >> 1 & 3);
  b.put(39, 1, BO & 1);
  b.put(38, 5, RH >> 1);
  b.put(32, 1, RH & 1);
  b.put(31, 7, GH);
  b.put(24, 1, BH >> 5);
  b.put(23, 5, BH & 31);
  b.put(18, 6, RV);
  b.put(12, 7, GV);
  b.put(5, 6, BV);
  b.put(33, 1, 1);
  // Dummy bits: R (63, RO's top 4) + dR (RO's low 2, GO1) in range; G in range; B overflows.
  const int B = (BO >> 3 & 3), dB = (BO >> 1 & 3);  // BO2 and BO3a
  if (B + dB > 3) {
    b.put(47, 3, 7);
    b.put(42, 1, 0);
  } else {
    b.put(47, 3, 0);
    b.put(42, 1, 1);
  }
  const Bits check = b;
  const int R = check.range(63, 59) + sext3(check.range(58, 56));
  const int G = check.range(55, 51) + sext3(check.range(50, 48));
  if (R < 0 || R > 31) b.put(63, 1, 1 - check.get({63}));
  if (G < 0 || G > 31) b.put(55, 1, 1 - check.get({55}));
  const int o[3] = {ext(RO, 6), ext(GO, 7), ext(BO, 6)}, h[3] = {ext(RH, 6), ext(GH, 7), ext(BH, 6)},
            v[3] = {ext(RV, 6), ext(GV, 7), ext(BV, 6)};
  std::vector<Px> want(16);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      int c[3];
      for (int k = 0; k < 3; ++k) c[k] = clamp8((x * (h[k] - o[k]) + y * (v[k] - o[k]) + 4 * o[k] + 2) >> 2);
      want[y * 4 + x] = {c[0], c[1], c[2], 255};
    }
  expect_rgba(TexelFormat::etc2_rgb_unorm, b.bytes(), want, "planar");
  expect_rgba(TexelFormat::etc2_rgba1_unorm, b.bytes(), want, "planar ignores the opaque bit");
}

// EAC: base 100, multiplier 3, table 13 (-1 -2 -3 -10 0 1 2 9): unsigned
// R11 gives 100 * 8 + 4 + m * 24; signed with base -128 is base -127;
// multiplier 0 adds the modifier unscaled; 8-bit alpha clamps.
TEST(EtcDecode, EacByHand) {
  Bits b;
  b.put(63, 8, 100);
  b.put(55, 4, 3);
  b.put(51, 4, 13);
  for (int k = 0; k < 16; ++k) b.put(47 - 3 * k, 3, k % 8);  // texel k (column-major) takes index k % 8
  const int mods[8] = {-1, -2, -3, -10, 0, 1, 2, 9};
  float t[16][4];
  decode(TexelFormat::eac_r11_unorm, b.bytes(), t);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) {
      const int k = x * 4 + y;
      EXPECT_FLOAT_EQ(t[y * 4 + x][0], float(100 * 8 + 4 + mods[k % 8] * 24) / 2047.0f) << k;
    }
  Bits s = b;
  s.put(63, 8, 0x80);  // -128, read as -127
  s.put(55, 4, 0);
  decode(TexelFormat::eac_r11_snorm, s.bytes(), t);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) {
      const int k = x * 4 + y;
      EXPECT_FLOAT_EQ(t[y * 4 + x][0], float(std::max(-1023, -127 * 8 + mods[k % 8])) / 1023.0f) << k;
    }
  // ETC2 RGBA8: alpha block first. 250 + 9 * 3 clamps to 255.
  Bits a = b;
  a.put(63, 8, 250);
  std::vector<std::uint8_t> rgba = a.bytes();
  Bits color;
  color.put(33, 1, 1);
  const auto cb = color.bytes();
  rgba.insert(rgba.end(), cb.begin(), cb.end());
  float u[16][4];
  decode_block(TexelFormat::etc2_rgba8_unorm, rgba.data(), u);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) {
      const int k = x * 4 + y;
      EXPECT_FLOAT_EQ(u[y * 4 + x][3], float(clamp8(250 + mods[k % 8] * 3)) / 255.0f) << k;
    }
}

// Every bit pattern is a block: texproc's decoders against the plain ones.
TEST(EtcDecode, RandomBlocksMatchThePlainDecoder) {
  std::mt19937_64 rng(2026);
  for (int n = 0; n < 20000; ++n) {
    Bits b;
    b.v = rng();
    if (n % 4 == 1) b.put(33, 1, 1);  // more differential-family blocks (T, H, planar)
    const auto bytes = b.bytes();
    expect_rgba(TexelFormat::etc2_rgb_unorm, bytes, plain_etc2(b, false), "etc2");
    expect_rgba(TexelFormat::etc2_rgba1_unorm, bytes, plain_etc2(b, true), "etc2 punch-through");
    expect_rgba(TexelFormat::etc1_rgb, bytes, plain_etc2(b, false, true), "etc1");
    float t[16][4];
    for (int kind = 1; kind <= 2; ++kind) {
      decode(kind == 1 ? TexelFormat::eac_r11_unorm : TexelFormat::eac_r11_snorm, bytes, t);
      const auto want = plain_eac(b, kind);
      for (int i = 0; i < 16; ++i) ASSERT_EQ(t[i][0], float(want[i]) / (kind == 1 ? 2047.0f : 1023.0f)) << n;
    }
    std::vector<std::uint8_t> rgba = bytes;
    rgba.insert(rgba.end(), bytes.begin(), bytes.end());
    decode_block(TexelFormat::etc2_rgba8_unorm, rgba.data(), t);
    const auto alpha = plain_eac(b, 0);
    for (int i = 0; i < 16; ++i) ASSERT_EQ(std::lround(t[i][3] * 255), alpha[i]) << n;
    decode_block(TexelFormat::eac_rg11_snorm, rgba.data(), t);
    const auto s = plain_eac(b, 2);
    for (int i = 0; i < 16; ++i) ASSERT_EQ(t[i][1], float(s[i]) / 1023.0f) << n;
  }
}

// The decoder's sub-block palette (SSE2's saturating pack as the clamp,
// where the target has it) gives the plain reference's words for every
// table and every value of each channel, the clamps at both ends included.
TEST(EtcDecode, SubBlockPaletteMatchesThePlainReference) {
  for (int table = 0; table < 8; ++table)
    for (int v = 0; v < 256; ++v) {
      const int c[3] = {v, 255 - v, (v * 7 + 3) & 255};
      std::uint32_t want[4], got[4];
      etc::sub_block_palette_scalar(c, table, want);
      etc::sub_block_palette(c, table, got);
      for (int i = 0; i < 4; ++i) ASSERT_EQ(got[i], want[i]) << "table " << table << " value " << v << " index " << i;
      EXPECT_EQ(want[0] >> 24, 255u);
    }
}

// ETC1 against android-libetc1's decoder (the library behind etc1tool), on
// random valid ETC1 blocks (differential blocks whose second colour stays in
// range).
TEST(EtcDecode, Etc1MatchesLibEtc1) {
  std::mt19937_64 rng(7);
  int compared = 0;
  for (int n = 0; n < 20000; ++n) {
    Bits b;
    b.v = rng();
    if (b.get({33})) {
      bool valid = true;
      for (int k = 0; k < 3; ++k) {
        const int c = b.range(63 - 8 * k, 59 - 8 * k) + sext3(b.range(58 - 8 * k, 56 - 8 * k));
        valid &= c >= 0 && c <= 31;
      }
      if (!valid) continue;
    }
    const auto bytes = b.bytes();
    etc1_byte rgb[48];
    etc1_decode_block(bytes.data(), rgb);
    std::vector<Px> want(16);
    for (int i = 0; i < 16; ++i) want[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 255};
    expect_rgba(TexelFormat::etc1_rgb, bytes, want, "libetc1");
    ++compared;
  }
  EXPECT_GT(compared, 10000);
}

// ---------------------------------------------------------------------------
// Encoding.

namespace {

// A 4x4 RGBA8 image of decoded texels.
Image image_of(const float t[16][4], int channels) {
  Image img = Image::uninitialized(4, 4, channels, PixelType::u8);
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < channels; ++c)
      img.row<std::uint8_t>(i / 4)[(i % 4) * channels + c] = std::uint8_t(std::lround(t[i][c] * 255));
  return img;
}

// Encodes the decoded texels of `block` at `high` and checks that they
// decode back exactly.
void expect_exact_round_trip(TexelFormat f, const std::vector<std::uint8_t>& block, const char* what, int n) {
  float want[16][4], got[16][4];
  decode_block(f, block.data(), want);
  const Image img = image_of(want, 4);
  const std::vector<std::uint8_t> enc = compress_image(img.view(), f, Quality::high);
  decode_block(f, enc.data(), got);
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) {
      ASSERT_EQ(got[i][c], want[i][c]) << what << " block " << n << " texel " << i << " channel " << c << ": "
                                       << std::hex << Bits::of(block.data()).v << " encoded as "
                                       << Bits::of(enc.data()).v;
    }
}

// Indices 0..3, four of each, shuffled.
void balanced_indices(Bits& b, std::mt19937& rng) {
  int idx[16];
  for (int i = 0; i < 16; ++i) idx[i] = i % 4;
  std::shuffle(idx, idx + 16, rng);
  for (int k = 0; k < 16; ++k) {
    b.put(k + 16, 1, idx[k] >> 1);
    b.put(k, 1, idx[k] & 1);
  }
}

int pick(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// 61x37 RGBA: smooth gradients on the left, noise on the right, alpha both.
Image random_smooth_or_noise() {
  const Image noise = random_image(61, 37, 4, PixelType::u8, 3);
  Image img = noise;
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 30; ++x) {
      std::uint8_t* p = img.row<std::uint8_t>(y) + x * 4;
      p[0] = std::uint8_t(x * 8);
      p[1] = std::uint8_t(y * 6);
      p[2] = std::uint8_t(128 + (x - y));
      p[3] = std::uint8_t(x * 8);
    }
  return img;
}

}  // namespace

// Blocks built to be exactly representable in one mode (no clamping, every
// index used) come back exactly after encoding at `high`.
TEST(EtcEncode, EachModeRoundTripsExactly) {
  std::mt19937 rng(11);
  for (int n = 0; n < 40; ++n) {
    // Individual: 4-bit colours 4..11, tables 0..3.
    Bits ind;
    for (int c = 0; c < 3; ++c) {
      ind.put(63 - 8 * c, 4, pick(rng, 4, 11));
      ind.put(59 - 8 * c, 4, pick(rng, 4, 11));
    }
    ind.put(39, 3, pick(rng, 0, 3));
    ind.put(36, 3, pick(rng, 0, 3));
    ind.put(33, 1, 0);
    ind.put(32, 1, pick(rng, 0, 1));
    balanced_indices(ind, rng);
    expect_exact_round_trip(TexelFormat::etc1_rgb, ind.bytes(), "individual", n);
    // Differential: 5-bit bases 8..23, deltas -2..2.
    Bits dif;
    for (int c = 0; c < 3; ++c) {
      dif.put(63 - 8 * c, 5, pick(rng, 8, 23));
      dif.put(58 - 8 * c, 3, pick(rng, -2, 2) & 7);
    }
    dif.put(39, 3, pick(rng, 0, 3));
    dif.put(36, 3, pick(rng, 0, 3));
    dif.put(33, 1, 1);
    dif.put(32, 1, pick(rng, 0, 1));
    balanced_indices(dif, rng);
    expect_exact_round_trip(TexelFormat::etc1_rgb, dif.bytes(), "differential", n);
    expect_exact_round_trip(TexelFormat::etc2_rgb_unorm, dif.bytes(), "differential (ETC2)", n);
    // T: C1 dark, C2 bright, distances 3..11.
    Bits t;
    const int r1 = pick(rng, 2, 4);
    t.put(60, 2, r1 >> 2);
    t.put(57, 2, r1 & 3);
    t.put(55, 4, pick(rng, 2, 4));
    t.put(51, 4, pick(rng, 2, 4));
    t.put(47, 4, pick(rng, 11, 12));
    t.put(43, 4, pick(rng, 11, 12));
    t.put(39, 4, pick(rng, 11, 12));
    const int td = pick(rng, 0, 2);
    t.put(35, 2, td >> 1);
    t.put(32, 1, td & 1);
    t.put(33, 1, 1);
    if ((r1 >> 2) + (r1 & 3) > 3) {
      t.put(63, 3, 7);
      t.put(58, 1, 0);
    } else {
      t.put(63, 3, 0);
      t.put(58, 1, 1);
    }
    balanced_indices(t, rng);
    ASSERT_EQ(plain_etc2(t, false)[0].a, 255);
    expect_exact_round_trip(TexelFormat::etc2_rgb_unorm, t.bytes(), "T", n);
    // H: two colour pairs C1 +- d and C2 +- d.
    Bits h;
    const int hr1 = pick(rng, 2, 4), hg1 = pick(rng, 2, 4), hb1 = pick(rng, 2, 4);
    h.put(62, 4, hr1);
    h.put(58, 3, hg1 >> 1);
    h.put(52, 1, hg1 & 1);
    h.put(51, 1, hb1 >> 3);
    h.put(49, 2, hb1 >> 1 & 3);
    h.put(47, 1, hb1 & 1);
    const int hg2 = pick(rng, 11, 12);
    h.put(46, 4, pick(rng, 11, 12));
    h.put(42, 3, hg2 >> 1);
    h.put(39, 1, hg2 & 1);
    h.put(38, 4, pick(rng, 11, 12));
    h.put(34, 1, 0);
    h.put(32, 1, pick(rng, 0, 1));
    h.put(33, 1, 1);
    {
      const int s = hr1 + sext3(hg1 >> 1);
      h.put(63, 1, s < 0 ? 1 : 0);
      const int g = (hg1 & 1) * 2 + (hb1 >> 3), bb = hb1 >> 1 & 3;
      if (g + bb > 3) {
        h.put(55, 3, 7);
        h.put(50, 1, 0);
      } else {
        h.put(55, 3, 0);
        h.put(50, 1, 1);
      }
    }
    balanced_indices(h, rng);
    expect_exact_round_trip(TexelFormat::etc2_rgb_unorm, h.bytes(), "H", n);
    // Planar: O, H, V near each other (no clamping).
    Bits p;
    const int ro = pick(rng, 24, 40), go = pick(rng, 48, 80), bo = pick(rng, 24, 40);
    const int rh = pick(rng, 24, 40), gh = pick(rng, 48, 80), bh = pick(rng, 24, 40);
    const int rv = pick(rng, 24, 40), gv = pick(rng, 48, 80), bv = pick(rng, 24, 40);
    p.put(62, 6, ro);
    p.put(56, 1, go >> 6);
    p.put(54, 6, go & 63);
    p.put(48, 1, bo >> 5);
    p.put(44, 2, bo >> 3 & 3);
    p.put(41, 2, bo >> 1 & 3);
    p.put(39, 1, bo & 1);
    p.put(38, 5, rh >> 1);
    p.put(32, 1, rh & 1);
    p.put(31, 7, gh);
    p.put(24, 1, bh >> 5);
    p.put(23, 5, bh & 31);
    p.put(18, 6, rv);
    p.put(12, 7, gv);
    p.put(5, 6, bv);
    p.put(33, 1, 1);
    if ((bo >> 3 & 3) + (bo >> 1 & 3) > 3) {
      p.put(47, 3, 7);
      p.put(42, 1, 0);
    } else {
      p.put(47, 3, 0);
      p.put(42, 1, 1);
    }
    for (int hi : {63, 55}) {
      const int lo3 = hi - 5;
      if (int(p.range(hi, hi - 4)) + sext3(p.range(lo3, lo3 - 2)) > 31 ||
          int(p.range(hi, hi - 4)) + sext3(p.range(lo3, lo3 - 2)) < 0) {
        p.put(hi, 1, 1 - p.get({hi}));
      }
    }
    expect_exact_round_trip(TexelFormat::etc2_rgb_unorm, p.bytes(), "planar", n);
    // EAC: base mid-range, multiplier 1..4, every index twice.
    Bits e;
    e.put(63, 8, pick(rng, 60, 190));
    e.put(55, 4, pick(rng, 1, 4));
    e.put(51, 4, pick(rng, 0, 15));
    int ix[16];
    for (int i = 0; i < 16; ++i) ix[i] = i % 8;
    std::shuffle(ix, ix + 16, rng);
    for (int k = 0; k < 16; ++k) e.put(47 - 3 * k, 3, ix[k]);
    float want[16][4], got[16][4];
    for (TexelFormat f : {TexelFormat::eac_r11_unorm, TexelFormat::eac_r11_snorm}) {
      const bool s = f == TexelFormat::eac_r11_snorm;
      Bits eb = e;
      if (s) eb.put(63, 8, pick(rng, -60, 60) & 255);
      decode_block(f, eb.bytes().data(), want);
      // The targets as 16-bit data: EAC's 11 bits survive the trip.
      Image img = Image::uninitialized(4, 4, 1, PixelType::f32);
      for (int i = 0; i < 16; ++i) img.row<float>(i / 4)[i % 4] = s ? (want[i][0] + 1.0f) * 0.5f : want[i][0];
      const auto enc = compress_image(img.view(), f, Quality::high);
      decode_block(f, enc.data(), got);
      for (int i = 0; i < 16; ++i) ASSERT_NEAR(got[i][0], want[i][0], 1e-6) << "EAC block " << n << " texel " << i;
    }
    // EAC alpha in ETC2 RGBA8 (with an exact colour block).
    std::vector<std::uint8_t> rgba = e.bytes();
    const auto color = dif.bytes();
    rgba.insert(rgba.end(), color.begin(), color.end());
    expect_exact_round_trip(TexelFormat::etc2_rgba8_unorm, rgba, "ETC2 RGBA8 alpha", n);
  }
}

// Punch-through: texels with alpha < 128 decode transparent, the others opaque.
TEST(EtcEncode, PunchThroughKeepsTheCutout) {
  std::mt19937 rng(5);
  Image img = Image::uninitialized(16, 16, 4, PixelType::u8);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      std::uint8_t* p = img.row<std::uint8_t>(y) + x * 4;
      p[0] = std::uint8_t(x * 16);
      p[1] = std::uint8_t(y * 16);
      p[2] = 128;
      p[3] = (x + y) % 3 == 0 ? 0 : (x * y) % 5 == 0 ? 100 : 255;
    }
  const Image d = round_trip(img, TexelFormat::etc2_rgba1_unorm, Quality::normal, PixelType::u8);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool visible = img.row<std::uint8_t>(y)[x * 4 + 3] >= 128;
      EXPECT_EQ(d.row<std::uint8_t>(y)[x * 4 + 3], visible ? 255 : 0) << x << "," << y;
    }
}

// ETC2 RGBA8's alpha (EAC, 8 bits) comes back exactly where a block's alpha
// spans at most six consecutive levels (table 13's modifiers -3..2 at
// multiplier 1), at every quality: `fast` missed it before (its multiplier
// rounds to 0 there, a flat palette), e.g. the 254/255 edges of cutouts.
// The same bytes on every SIMD target.
TEST(EtcEncode, NarrowAlphaIsLossless) {
  std::mt19937 rng(5);
  Image img(64, 32, 4, PixelType::u8);
  for (int by = 0; by < 8; ++by)
    for (int bx = 0; bx < 16; ++bx) {
      const int a = int(rng() % 256), width = 1 + bx % 6;  // levels a .. a + width - 1 (at most 255)
      for (int i = 0; i < 16; ++i) {
        std::uint8_t* p = img.row<std::uint8_t>(by * 4 + i / 4) + 4 * (bx * 4 + i % 4);
        p[0] = std::uint8_t(bx * 16);
        p[1] = 90;
        p[2] = std::uint8_t(by * 30);
        p[3] = std::uint8_t(std::min(255, a + int(rng() % width)));
      }
    }
  for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
    const Image d = round_trip(img, TexelFormat::etc2_rgba8_unorm, q, PixelType::u8);
    int wrong = 0;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x) wrong += d.row<std::uint8_t>(y)[4 * x + 3] != img.row<std::uint8_t>(y)[4 * x + 3];
    EXPECT_EQ(wrong, 0) << to_string(q);
    expect_same_on_every_target([&] { return compress_image(img.view(), TexelFormat::etc2_rgba8_unorm, q); },
                                std::string("narrow alpha ") + to_string(q));
  }
}

// A block of one colour gets the least error the format allows at every
// quality. ETC1: an exhaustive oracle here (every mode, table, modifier and
// per-channel base of a block whose texels all take one modifier, which is
// the best a flat block can do, each texel choosing alone). ETC2 (and
// punch-through's opaque blocks, differential only): never above that
// oracle, and the same error at every level (its planar mode's tilted
// planes do better still). `fast` was 2.8x the optimum's error for ETC1.
TEST(EtcEncode, FlatBlocksAreOptimal) {
  auto ext = [](int q, int bits) { return bits == 5 ? (q << 3 | q >> 2) : (q << 4 | q); };
  auto oracle = [&](const int c[3], bool individual) {
    long best = -1;
    for (int bits = 4; bits <= 5; ++bits) {
      if (bits == 4 && !individual) continue;
      for (int t = 0; t < 8; ++t)
        for (int i = 0; i < 4; ++i) {
          static const int kMods[8][4] = {{2, 8, -2, -8},       {5, 17, -5, -17},    {9, 29, -9, -29},
                                          {13, 42, -13, -42},   {18, 60, -18, -60},  {24, 80, -24, -80},
                                          {33, 106, -33, -106}, {47, 183, -47, -183}};
          long e = 0;
          for (int ch = 0; ch < 3; ++ch) {
            long be = -1;
            for (int q = 0; q < (1 << bits); ++q) {
              const long d = c[ch] - std::clamp(ext(q, bits) + kMods[t][i], 0, 255);
              if (be < 0 || d * d < be) be = d * d;
            }
            e += be;
          }
          if (best < 0 || 16 * e < best) best = 16 * e;
        }
    }
    return best;
  };
  std::mt19937 rng(8);
  for (int n = 0; n < 120; ++n) {
    const int c[3] = {int(rng() % 256), int(rng() % 256), int(rng() % 256)};
    Image img(4, 4, 4, PixelType::u8);
    for (int i = 0; i < 16; ++i)
      for (int ch = 0; ch < 4; ++ch)
        img.row<std::uint8_t>(i / 4)[4 * (i % 4) + ch] = std::uint8_t(ch == 3 ? 255 : c[ch]);
    for (TexelFormat f : {TexelFormat::etc1_rgb, TexelFormat::etc2_rgb_unorm, TexelFormat::etc2_rgba1_unorm}) {
      const long limit = oracle(c, f != TexelFormat::etc2_rgba1_unorm);
      long first = -1;
      for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
        const Image d = round_trip(img, f, q, PixelType::u8);
        long e = 0;
        for (int i = 0; i < 16; ++i)
          for (int ch = 0; ch < 3; ++ch) {
            const long diff = long(d.row<std::uint8_t>(i / 4)[d.channels() * (i % 4) + ch]) - c[ch];
            e += diff * diff;
          }
        if (f == TexelFormat::etc1_rgb) {
          EXPECT_EQ(e, limit) << c[0] << "," << c[1] << "," << c[2] << " " << to_string(q);
        } else {
          EXPECT_LE(e, limit) << format_info(f).name << " " << c[0] << "," << c[1] << "," << c[2] << " "
                              << to_string(q);
        }
        if (first < 0) first = e;
        EXPECT_EQ(e, first) << format_info(f).name << " " << to_string(q) << ": every level the same";
      }
    }
  }
}

// Punch-through: one visible colour among holes. The holes stay holes, and
// every level reaches at least the best differential block with the opaque
// flag clear (modifiers 0 and +-b, worked out here exhaustively), the same
// error at every level. `fast` had 2.5 times `high`'s error before.
TEST(EtcEncode, PunchThroughOneColourWithHoles) {
  static const int kB[8] = {8, 17, 29, 42, 60, 80, 106, 183};
  std::mt19937 rng(14);
  for (int n = 0; n < 100; ++n) {
    const int c[3] = {int(rng() % 256), int(rng() % 256), int(rng() % 256)};
    Image img(4, 4, 4, PixelType::u8);
    int visible = 0;
    for (int i = 0; i < 16; ++i) {
      std::uint8_t* p = img.row<std::uint8_t>(i / 4) + 4 * (i % 4);
      p[0] = std::uint8_t(c[0]);
      p[1] = std::uint8_t(c[1]);
      p[2] = std::uint8_t(c[2]);
      p[3] = (i * 5 + n) % 4 == 0 ? 0 : 255;
      visible += p[3] == 255;
    }
    long oracle = -1;
    for (int option = 0; option < 17; ++option) {
      const int m = option == 0 ? 0 : (option % 2 ? kB[(option - 1) / 2] : -kB[(option - 1) / 2]);
      long e = 0;
      for (int ch = 0; ch < 3; ++ch) {
        long be = -1;
        for (int q = 0; q < 32; ++q) {
          const long d = c[ch] - std::clamp((q << 3 | q >> 2) + m, 0, 255);
          if (be < 0 || d * d < be) be = d * d;
        }
        e += be;
      }
      if (oracle < 0 || e < oracle) oracle = e;
    }
    long first = -1;
    for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max}) {
      const Image d = round_trip(img, TexelFormat::etc2_rgba1_unorm, q, PixelType::u8);
      long e = 0;
      for (int i = 0; i < 16; ++i) {
        const std::uint8_t* p = d.row<std::uint8_t>(i / 4) + d.channels() * (i % 4);
        const bool hole = img.row<std::uint8_t>(i / 4)[4 * (i % 4) + 3] == 0;
        EXPECT_EQ(p[3], hole ? 0 : 255) << i;
        if (!hole)
          for (int ch = 0; ch < 3; ++ch) e += long(p[ch] - c[ch]) * (p[ch] - c[ch]);
      }
      EXPECT_LE(e, oracle * visible) << c[0] << "," << c[1] << "," << c[2] << " " << to_string(q);
      if (first < 0) first = e;
      EXPECT_EQ(e, first) << to_string(q);
    }
  }
}

// ETC2 `fast`: a block of exactly two colours (text, line art) is at most
// the error of its two colours rounded to 4 bits a channel (what the T mode
// holds exactly: one colour at paint 0, the other at paint 2), where its
// ETC1 block alone was 40 times that on random pairs.
TEST(EtcEncode, TwoColourBlocksAtFast) {
  std::mt19937 rng(21);
  for (int n = 0; n < 100; ++n) {
    int c[2][3];
    for (auto& cc : c)
      for (int& v : cc) v = int(rng() % 256);
    std::uint8_t px[16][4];
    long bound = 0;
    for (int i = 0; i < 16; ++i) {
      const int* col = c[(i * 3 + n) % 4 == 0 ? 1 : 0];
      for (int ch = 0; ch < 3; ++ch) {
        px[i][ch] = std::uint8_t(col[ch]);
        const int rounded = 17 * ((col[ch] + 8) / 17);  // the nearest 4-bit level, extended
        bound += long(col[ch] - rounded) * (col[ch] - rounded);
      }
      px[i][3] = 255;
    }
    std::uint8_t block[8];
    encode_block(TexelFormat::etc2_rgb_unorm, px, Quality::fast, block);
    float t[16][4];
    decode_block(TexelFormat::etc2_rgb_unorm, block, t);
    long e = 0;
    for (int i = 0; i < 16; ++i)
      for (int ch = 0; ch < 3; ++ch) {
        const long d = std::lround(t[i][ch] * 255.0f) - px[i][ch];
        e += d * d;
      }
    EXPECT_LE(e, bound) << n;
  }
}

// An ETC1 stream is an ETC2 stream: the ETC2 decoder reads every block the
// ETC1 encoder writes as the ETC1 decoder does; and bytes do not depend on
// the thread count.
TEST(EtcEncode, Etc1StreamsAreEtc2AndThreadsDoNotMatter) {
  const Image img = random_smooth_or_noise();
  for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
    const auto etc1 = compress_image(img.view(), TexelFormat::etc1_rgb, q);
    for (std::size_t b = 0; b < etc1.size(); b += 8) {
      float a[16][4], c[16][4];
      decode_block(TexelFormat::etc1_rgb, etc1.data() + b, a);
      decode_block(TexelFormat::etc2_rgb_unorm, etc1.data() + b, c);
      for (int i = 0; i < 16; ++i)
        for (int k = 0; k < 4; ++k) ASSERT_EQ(a[i][k], c[i][k]) << "block " << b / 8;
    }
  }
  for (TexelFormat f : {TexelFormat::etc2_rgb_unorm, TexelFormat::etc2_rgba8_unorm, TexelFormat::etc2_rgba1_unorm,
                        TexelFormat::eac_rg11_snorm}) {
    auto encode = [&] { return compress_image(img.view(), f, Quality::normal); };
    EXPECT_EQ(with_threads(1, encode), with_threads(2, encode)) << format_info(f).name;
  }
}

// The SIMD twins (half-block scoring; EAC's nearest-of-8) give the scalar
// reference's bytes on every target this CPU supports, for every format and
// quality.
TEST(EtcEncode, SimdMatchesScalarOnEveryTarget) {
  const Image img = random_smooth_or_noise();
  for (TexelFormat f : {TexelFormat::etc1_rgb, TexelFormat::etc2_rgb_unorm, TexelFormat::etc2_rgba1_unorm,
                        TexelFormat::etc2_rgba8_unorm, TexelFormat::eac_r11_unorm, TexelFormat::eac_rg11_snorm}) {
    for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
      expect_same_on_every_target([&] { return compress_image(img.view(), f, q); },
                                  std::string(format_info(f).name) + " " + to_string(q));
    }
  }
  // The lanes encode 16 blocks at a time: 21 blocks a row (a batch of 16, one
  // of 5) read straight from whole rows, with halves far apart (individual
  // mode) in some blocks and not in others.
  Image wide = random_image(84, 8, 4, PixelType::u8, 5);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 84; ++x)
      if ((x / 4) % 3 == 0)
        for (int c = 0; c < 3; ++c) wide.row<std::uint8_t>(y)[4 * x + c] = std::uint8_t(x % 4 < 2 ? 20 + y : 230 - y);
  for (TexelFormat f : {TexelFormat::etc1_rgb, TexelFormat::etc2_rgba8_unorm}) {
    expect_same_on_every_target([&] { return compress_image(wide.view(), f, Quality::fast); },
                                std::string(format_info(f).name) + " fast, whole rows");
  }
  // Punch-through: its opaque blocks go through the lanes (differential mode
  // only), the others block by block; here a third of the blocks are opaque.
  Image cutout = wide;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 84; ++x) cutout.row<std::uint8_t>(y)[4 * x + 3] = (x / 4) % 3 == 1 ? 255 : std::uint8_t(x * 3);
  for (Quality q : {Quality::fast, Quality::normal, Quality::high})
    expect_same_on_every_target([&] { return compress_image(cutout.view(), TexelFormat::etc2_rgba1_unorm, q); },
                                std::string("etc2a1 ") + to_string(q) + ", whole rows");
  for (Quality q : {Quality::normal, Quality::high})
    for (TexelFormat f : {TexelFormat::etc1_rgb, TexelFormat::etc2_rgba8_unorm, TexelFormat::eac_r11_unorm,
                          TexelFormat::eac_rg11_snorm})
      expect_same_on_every_target([&] { return compress_image(wide.view(), f, q); },
                                  std::string(format_info(f).name) + " " + to_string(q) + ", whole rows");
}

// Line art: black with bright texels, where the decoder's clamping decides.
// A half of black texels and one bright one is exact with the far modifier
// (base = bright texel minus it; black texels take the negative one, which
// clamps to 0), far from the mean. `normal` seeds the base from the extreme
// texels (before: 54x `max`'s error on one bright texel a block); `fast`
// estimates errors unclamped but tries the table whose far modifier reaches
// the farthest texel and re-picks modifiers under clamping (before: 4.7x
// libetc1's error on sparse bright texels, 12x on one a block).
TEST(EtcEncode, LineArtFindsClampedModifiers) {
  for (int kind = 0; kind < 2; ++kind) {
    std::mt19937 rng(7);
    Image img = Image::uninitialized(64, 64, 4, PixelType::u8);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        std::uint8_t* p = img.row<std::uint8_t>(y) + 4 * x;
        const int v = kind == 0 && pick(rng, 0, 7) == 0 ? pick(rng, 120, 255) : 0;  // kind 0: sparse bright texels
        p[0] = p[1] = p[2] = std::uint8_t(v);
        p[3] = 255;
      }
    for (int b = 0; kind == 1 && b < 256; ++b) {  // kind 1: one bright texel a block
      std::uint8_t* p = img.row<std::uint8_t>(4 * (b / 16) + pick(rng, 0, 3)) + 4 * (4 * (b % 16) + pick(rng, 0, 3));
      p[0] = p[1] = p[2] = std::uint8_t(pick(rng, 120, 255));
    }
    auto squared_error = [&](const std::vector<std::uint8_t>& blocks) {
      const Image d = decompress_image(blocks, 64, 64, TexelFormat::etc1_rgb, PixelType::u8);
      double se = 0;
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          for (int c = 0; c < 3; ++c)
            se +=
                std::pow(double(d.row<std::uint8_t>(y)[d.channels() * x + c]) - img.row<std::uint8_t>(y)[4 * x + c], 2);
      return se;
    };
    std::vector<std::uint8_t> rgb(64 * 64 * 3), libetc1(etc1_get_encoded_data_size(64, 64));
    for (int i = 0; i < 64 * 64; ++i)
      for (int c = 0; c < 3; ++c) rgb[3 * i + c] = img.data()[4 * i + c];
    etc1_encode_image(rgb.data(), 64, 64, 3, 64 * 3, libetc1.data());
    auto at = [&](Quality q) { return squared_error(compress_image(img.view(), TexelFormat::etc1_rgb, q)); };
    const double best = at(Quality::max);
    EXPECT_LT(at(Quality::fast), 1.6 * squared_error(libetc1)) << "kind " << kind;
    EXPECT_LT(at(Quality::normal), kind == 1 ? 3 * best : 1.5 * best) << "kind " << kind;
    EXPECT_LT(at(Quality::high), 1.1 * best) << "kind " << kind;
  }
}
