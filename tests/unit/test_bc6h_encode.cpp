// BC6H encoding: the packing against texels worked out from the
// specification's equations for every mode and partition (UF16 and SF16),
// the quantizer against a brute-force search, one-colour blocks (every
// half), values far above 1, the quality levels' order, SIMD against the
// scalar reference on corpus crops, thread counts, and Pillow (an
// independent decoder) reading the encoder's blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <Imath/half.h>

#include "bc/bc6h_lanes.h"
#include "bc/bc6h_shared.h"
#include "bc/bc_decode.h"
#include "support/images.h"
#include "support/targets.h"
#include "support/threads.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"
#include "texproc/container.h"
#include "texproc/texture.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

// The extension's equations, written here again (not through bc6h_shared.h):
// an endpoint of `bits` bits unquantized to 16, and the final scaling to
// half bits.
int spec_unquantize(int x, int bits, bool is_signed) {
  if (!is_signed) {
    if (bits >= 15) return x;
    if (x == 0) return 0;
    if (x == (1 << bits) - 1) return 0xFFFF;
    return ((x << 16) + 0x8000) >> bits;
  }
  if (bits >= 16) return x;
  const int m = std::abs(x);
  int unq;
  if (m == 0)
    unq = 0;
  else if (m >= (1 << (bits - 1)) - 1)
    unq = 0x7FFF;
  else
    unq = ((m << 15) + 0x4000) >> (bits - 1);
  return x < 0 ? -unq : unq;
}
std::uint16_t spec_finish(int v, bool is_signed) {
  if (!is_signed) return std::uint16_t((v * 31) / 64);
  return v < 0 ? std::uint16_t(0x8000 | ((-v * 31) / 32)) : std::uint16_t((v * 31) / 32);
}

void expected_texels(const bc6h::Choice& c, bool is_signed, std::uint16_t out[16][3]) {
  const bptc::Bc6hMode& M = bptc::kBc6hModes[c.mode];
  const bool two = M.partition_bits > 0;
  const std::uint8_t* w = two ? bptc::kWeights3 : bptc::kWeights4;
  for (int i = 0; i < 16; ++i) {
    const int s = two ? int(bptc::kPartitions2[c.partition] >> (2 * i) & 3) : 0;
    for (int ch = 0; ch < 3; ++ch) {
      const int a = spec_unquantize(c.code[2 * s][ch], M.endpoint_bits, is_signed);
      const int b = spec_unquantize(c.code[2 * s + 1][ch], M.endpoint_bits, is_signed);
      const int wi = w[c.index[i]];
      out[i][ch] = spec_finish(((64 - wi) * a + wi * b + 32) >> 6, is_signed);
    }
  }
}

// A random code of `bits` bits: UF16 [0, 2^bits), SF16 two's complement.
int random_code(std::mt19937& rng, int bits, bool is_signed) {
  const int v = int(rng() % (1u << bits));
  return is_signed && v >= 1 << (bits - 1) ? v - (1 << bits) : v;
}

// An f32 RGB image of `w` x `h` with values over many exponents (a sky:
// 2^-10 to 2^8 from top to bottom, a 10% ripple across, 5% noise); with
// negatives, the left half negated.
Image hdr_image(int w, int h, unsigned seed, bool with_negatives) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Image img(w, h, 3, PixelType::f32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float base = std::exp2(-10.0f + 18.0f * float(y) / float(h)) * (1.0f + 0.1f * std::sin(0.4f * float(x)));
      for (int c = 0; c < 3; ++c) {
        float v = base * (0.95f + 0.05f * u(rng)) * (c == 2 ? 1.3f : 1.0f);
        if (with_negatives && x < w / 2) v = -v;
        img.row<float>(y)[3 * x + c] = v;
      }
    }
  return img;
}

// A crop of a corpus HDR image as f32 RGB.
Image hdr_crop(const std::string& file, int x0, int y0, int w, int h) {
  const Image src = read_image(corpus_dir() + "/" + file);
  Image crop(w, h, 3, PixelType::f32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        crop.row<float>(y)[3 * x + c] = src.get(x0 + x, y0 + y, std::min(c, src.channels() - 1));
  return crop;
}

// The encoder's own error (bc6h_lanes.h): the squared differences of the
// decoded halves' finish values, each limited, summed; through texproc's
// decoder.
double search_error(const Image& img, const std::vector<std::uint8_t>& blocks, bool is_signed) {
  const int bw = (img.width() + 3) / 4;
  double se = 0;
  for (int by = 0; by < (img.height() + 3) / 4; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      std::uint16_t h[16][3];
      bc::decode_bc6h(&blocks[(std::size_t(by) * bw + bx) * 16], is_signed, h);
      for (int i = 0; i < 16; ++i) {
        const int x = std::min(4 * bx + i % 4, img.width() - 1), y = std::min(4 * by + i / 4, img.height() - 1);
        for (int c = 0; c < 3; ++c) {
          const float v = std::clamp(img.row<const float>(y)[3 * x + c], -65504.0f, 65504.0f);
          const int want = bc6h::target(Imath::half(v).bits(), is_signed);
          const int got = bc6h::target(h[i][c], is_signed);
          const double d = std::min(std::abs(want - got), bc6h::kErrorLimit);
          se += d * d;
        }
      }
    }
  return se;
}

}  // namespace

// Random Choices of every mode on every partition it has, UF16 and SF16,
// the transformed modes' endpoints within a delta's reach of the base: the
// packed block decodes (texproc's decoder, which matches Pillow's on random
// blocks) to the texels the equations give.
TEST(Bc6hEncode, EveryModeAndPartitionPacksWhatTheDecoderReads) {
  std::mt19937 rng(5);
  int checked = 0;
  for (bool is_signed : {false, true})
    for (int k = 0; k < 14; ++k) {
      const bptc::Bc6hMode& M = bptc::kBc6hModes[k];
      const int partitions = M.partition_bits ? 32 : 1, ends = M.partition_bits ? 4 : 2;
      for (int part = 0; part < partitions; ++part)
        for (int rep = 0; rep < 4; ++rep) {
          bc6h::Choice c;
          c.mode = k;
          c.partition = part;
          const int eb = M.endpoint_bits, mask = (1 << eb) - 1;
          for (int ch = 0; ch < 3; ++ch) {
            c.code[0][ch] = random_code(rng, eb, is_signed);
            for (int j = 1; j < ends; ++j) {
              if (!M.transformed) {
                c.code[j][ch] = random_code(rng, eb, is_signed);
                continue;
              }
              // base + delta, wrapped to the endpoint bits as the decoder does
              const int delta = random_code(rng, M.delta_bits[ch], true);
              const int sum = (c.code[0][ch] + delta) & mask;
              c.code[j][ch] = is_signed && sum >= 1 << (eb - 1) ? sum - (1 << eb) : sum;
            }
          }
          const int bits = M.partition_bits ? 3 : 4;
          const int anchor1 = M.partition_bits ? bptc::kAnchor2[part] : -1;
          for (int i = 0; i < 16; ++i)
            c.index[i] = std::uint8_t(rng() % (1u << (i == 0 || i == anchor1 ? bits - 1 : bits)));
          std::uint8_t block[16];
          std::uint16_t want[16][3], got[16][3];
          bc6h::pack_block(c, block);
          expected_texels(c, is_signed, want);
          bc::decode_bc6h(block, is_signed, got);
          ASSERT_EQ(0, std::memcmp(want, got, sizeof want))
              << (is_signed ? "SF16" : "UF16") << " mode " << M.number << " partition " << part;
          ++checked;
        }
    }
  EXPECT_EQ(checked, 2 * 4 * (10 * 32 + 4));
}

// The quantizer gives the code whose unquantized value is nearest, for
// every endpoint width the modes use, against a search of every code.
TEST(Bc6hEncode, QuantizeFindsTheNearestCode) {
  std::mt19937 rng(9);
  for (bool is_signed : {false, true})
    for (int bits : {6, 7, 8, 9, 10, 11, 12, 16})
      for (int n = 0; n < 2000; ++n) {
        const float u = is_signed ? -32767.0f + 65534.0f * float(rng() % 100000) / 99999.0f
                                  : 65535.0f * float(rng() % 100000) / 99999.0f;
        const int q = bc6h::quantize(u, bits, is_signed);
        const int lo = is_signed ? -((1 << (bits - 1)) - 1) : 0,
                  hi = is_signed ? (1 << (bits - 1)) - 1 : (1 << bits) - 1;
        float best = INFINITY;
        for (int c = lo; c <= hi; ++c) best = std::min(best, std::fabs(float(spec_unquantize(c, bits, is_signed)) - u));
        ASSERT_EQ(std::fabs(float(spec_unquantize(q, bits, is_signed)) - u), best) << bits << " bits, u " << u;
      }
}

// A block of one colour decodes to exactly that colour, for every finite
// half (UF16: every non-negative one; SF16: both signs), on the SIMD lanes
// and the scalar reference alike.
TEST(Bc6hEncode, OneColourBlocksAreExactForEveryHalf) {
  for (bool is_signed : {false, true}) {
    std::vector<int> values;
    for (int h = 0; h <= bc6h::kMaxFinish; ++h) {
      values.push_back(h);
      if (is_signed && h > 0) values.push_back(-h);
    }
    for (bool scalar : {false, true}) {
      int wrong = 0;
      for (std::size_t v0 = 0; v0 < values.size(); v0 += kBc6hBatch) {
        std::int32_t texel[16][3][kBc6hBatch] = {};
        const int count = int(std::min<std::size_t>(kBc6hBatch, values.size() - v0));
        for (int k = 0; k < count; ++k)
          for (int i = 0; i < 16; ++i)
            for (int c = 0; c < 3; ++c) texel[i][c][k] = values[v0 + std::size_t(k)];
        std::uint8_t out[kBc6hBatch][16];
        if (scalar)
          ref::bc6h_encode_lanes(texel, count, is_signed, bc6h_level(Quality::fast), out);
        else
          bc6h_encode_lanes(texel, count, is_signed, bc6h_level(Quality::fast), out);
        for (int k = 0; k < count; ++k) {
          std::uint16_t h[16][3];
          bc::decode_bc6h(out[k], is_signed, h);
          for (int i = 0; i < 16; ++i)
            for (int c = 0; c < 3; ++c)
              if (bc6h::target(h[i][c], is_signed) != values[v0 + std::size_t(k)] && wrong++ < 5)
                ADD_FAILURE() << (is_signed ? "SF16" : "UF16") << " value " << values[v0 + std::size_t(k)]
                              << " decodes to " << h[i][c];
        }
      }
      EXPECT_EQ(wrong, 0) << (scalar ? "scalar" : "SIMD");
    }
  }
}

// Values far above 1 (up to 2^8) survive, each decoded texel within 10% of
// its input; SF16 keeps negative values and UF16 stores them as 0.
TEST(Bc6hEncode, HdrValuesSurviveAndSignsAreKept) {
  for (bool is_signed : {false, true}) {
    const Image img = hdr_image(64, 64, 3, is_signed);
    const TexelFormat f = is_signed ? TexelFormat::bc6h_sfloat : TexelFormat::bc6h_ufloat;
    const Image d = decompress_image(compress_image(img.view(), f, Quality::normal), 64, 64, f, PixelType::f32);
    double max_value = 0, worst = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c) {
          const float v = img.row<const float>(y)[3 * x + c], got = d.row<const float>(y)[d.channels() * x + c];
          const float want = is_signed ? v : std::max(v, 0.0f);
          max_value = std::max(max_value, double(got));
          if (want == 0.0f) {
            EXPECT_LE(std::fabs(got), 1e-3f);
            continue;
          }
          EXPECT_EQ(got < 0, want < 0) << x << "," << y;
          worst = std::max(worst, std::fabs(double(got) / double(want) - 1.0));
        }
    EXPECT_GT(max_value, 200.0);
    // A half's mantissa is linear within an octave, so a gradient of a
    // stop across a block bends up to 6% away from a palette's line: 10%.
    EXPECT_LT(worst, 0.10) << (is_signed ? "SF16" : "UF16");
  }
}

// On corpus crops (a sky, a matcap, a night sky): every level's error is no
// larger than the level below's, the SIMD lanes give the scalar
// reference's bytes on every target, and 1 and 2 threads the same bytes;
// SF16 on the same crops with every third channel negated.
TEST(Bc6hEncode, LevelsOrderAndSimdMatchesScalarOnCorpusCrops) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  for (const char* file :
       {"hdr/blender_world_forest.exr", "hdr/blender_matcap_metal_carpaint.exr", "hdr/blender_world_night.exr"}) {
    Image crop = hdr_crop(file, 200, 100, 72, 40);  // 18 blocks a row: a batch of 16 and one of 2
    for (bool is_signed : {false, true}) {
      if (is_signed)
        for (int y = 0; y < crop.height(); ++y)
          for (int x = 0; x < crop.width(); ++x)
            if ((x / 4 + y / 4) % 3 == 0) crop.row<float>(y)[3 * x + (x + y) % 3] *= -1.0f;
      const TexelFormat f = is_signed ? TexelFormat::bc6h_sfloat : TexelFormat::bc6h_ufloat;
      const std::string what = std::string(file) + (is_signed ? " SF16 " : " UF16 ");
      double last = INFINITY;
      for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max}) {
        const auto blocks = compress_image(crop.view(), f, q);
        const double e = search_error(crop, blocks, is_signed);
        EXPECT_LE(e, last) << what << to_string(q);
        last = e;
        if (q == Quality::max) continue;  // the same code as high, slower
        expect_same_on_every_target([&] { return compress_image(crop.view(), f, q); }, what + to_string(q));
        EXPECT_EQ(with_threads(1, [&] { return compress_image(crop.view(), f, q); }),
                  with_threads(2, [&] { return compress_image(crop.view(), f, q); }))
            << what << to_string(q);
      }
    }
  }
}

// Pillow 9.4 (an independent decoder) reads the encoder's UF16 blocks of a
// corpus sky as texproc's decoder does: its 8-bit texels (the halves clamped
// to [0, 1]) within one level of texproc's.
TEST(Bc6hEncode, PillowReadsTheEncodersBlocks) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  if (std::system("/usr/bin/python3 -c 'import PIL' >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3-pil not installed";
  const std::string dir = (fs::temp_directory_path() / "texproc_bc6h_enc_pil").string();
  fs::create_directories(dir);
  Image crop = hdr_crop("hdr/blender_world_courtyard.exr", 256, 128, 128, 128);
  for (int y = 0; y < 128; ++y)  // most texels into (0, 1), where 8 bits compare
    for (int x = 0; x < 3 * 128; ++x) crop.row<float>(y)[x] *= 0.5f;
  Texture t;
  t.format = TexelFormat::bc6h_ufloat;
  t.width = t.height = 128;
  t.levels = t.layers = t.faces = 1;
  t.images = {compress_image(crop.view(), t.format, Quality::normal)};
  write_texture(dir + "/b.dds", t);
  const std::string out = dir + "/px.bin";
  const std::string cmd = "/usr/bin/python3 -c \"from PIL import Image; im = Image.open('" + dir + "/b.dds'); open('" +
                          out + "', 'wb').write(im.mode.encode() + b' ' + im.tobytes())\" 2>" + dir + "/err.txt";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp_file(dir + "/err.txt");
  const std::string px = slurp_file(out);
  ASSERT_EQ(px.substr(0, 4), "RGB ");
  ASSERT_EQ(px.size(), 4 + std::size_t(128 * 128 * 3));
  const Image d = decompress_image(t.images[0], 128, 128, t.format, PixelType::f32);
  int wrong = 0, inside = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = std::clamp(d.row<const float>(y)[d.channels() * x + c], 0.0f, 1.0f);
        inside += v > 0.0f && v < 1.0f;
        const int mine = int(std::lround(v * 255.0f)),
                  theirs = std::uint8_t(px[4 + (std::size_t(y) * 128 + x) * 3 + c]);
        if (std::abs(mine - theirs) > 1 && wrong++ < 5)
          ADD_FAILURE() << x << "," << y << " channel " << c << ": " << mine << " vs Pillow " << theirs;
      }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(inside, 128 * 128);
  fs::remove_all(dir);
}
