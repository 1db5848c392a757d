// BC7 encoding: the packing against texels worked out from the
// specification's equations for every mode and partition, one-colour
// blocks, opaque alpha, the quality levels' order, SIMD against the scalar
// reference on corpus crops, and thread counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "bc/bc7_lanes.h"
#include "bc/bc7_shared.h"
#include "bc/bc_decode.h"
#include "support/images.h"
#include "support/targets.h"
#include "support/threads.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;

namespace {

// The texels a Choice stands for, from the extension's equations (written
// here again, not through the encoder's helpers): endpoints expanded with
// their p-bits, interpolated by the index weights, rotated back.
void expected_texels(const bc7::Choice& c, std::uint8_t out[16][4]) {
  const bptc::Bc7Mode& M = bptc::kBc7Modes[c.mode];
  const bool has_p = M.endpoint_pbits || M.shared_pbits;
  auto value = [&](int s, int k, int ch) {
    const int bits = ch < 3 ? M.color_bits : M.alpha_bits;
    if (bits == 0) return 255;
    const int n = bits + (has_p ? 1 : 0);
    const int v = has_p ? c.code[s][k][ch] << 1 | c.pbit[s][k] : c.code[s][k][ch];
    return (v << (8 - n) | v >> (2 * n - 8)) & 255;
  };
  const std::uint32_t part = M.subsets == 2   ? bptc::kPartitions2[c.partition]
                             : M.subsets == 3 ? bptc::kPartitions3[c.partition]
                                              : 0;
  const bool swap = c.mode == 4 && c.index_selection;
  const int cbits = swap ? M.index2_bits : M.index_bits,
            abits = M.index2_bits ? (swap ? M.index_bits : M.index2_bits) : cbits;
  const std::uint8_t* cw = cbits == 2 ? bptc::kWeights2 : cbits == 3 ? bptc::kWeights3 : bptc::kWeights4;
  const std::uint8_t* aw = abits == 2 ? bptc::kWeights2 : abits == 3 ? bptc::kWeights3 : bptc::kWeights4;
  for (int i = 0; i < 16; ++i) {
    const int s = M.subsets == 1 ? 0 : int(part >> (2 * i) & 3);
    int px[4];
    for (int ch = 0; ch < 3; ++ch)
      px[ch] = ((64 - cw[c.color_index[i]]) * value(s, 0, ch) + cw[c.color_index[i]] * value(s, 1, ch) + 32) >> 6;
    const int ai = M.index2_bits ? c.alpha_index[i] : c.color_index[i];
    px[3] = ((64 - aw[ai]) * value(s, 0, 3) + aw[ai] * value(s, 1, 3) + 32) >> 6;
    if (c.rotation) std::swap(px[3], px[c.rotation - 1]);
    for (int ch = 0; ch < 4; ++ch) out[i][ch] = std::uint8_t(px[ch]);
  }
}

Image crop_rgba8(const Image& src, int x0, int y0, int w, int h, bool force_opaque) {
  Image crop(w, h, 4, PixelType::u8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) {
        const int sc = std::min(c, src.channels() - 1);
        const bool alpha = c == 3;
        const float v = alpha && (force_opaque || src.channels() < 4)
                            ? 1.0f
                            : src.get(x0 + x, y0 + y, alpha ? sc : (src.channels() < 3 ? 0 : sc));
        crop.row<std::uint8_t>(y)[4 * x + c] = std::uint8_t(std::lround(v * 255.0f));
      }
  return crop;
}

double rgba_error(const Image& a, const std::vector<std::uint8_t>& blocks) {
  const Image d = decompress_image(blocks, a.width(), a.height(), TexelFormat::bc7_unorm, PixelType::u8);
  double se = 0.0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < 4 * a.width(); ++x) {
      const double e = double(a.row<const std::uint8_t>(y)[x]) - double(d.row<const std::uint8_t>(y)[x]);
      se += e * e;
    }
  return se;
}

}  // namespace

// Random Choices of every mode, on every partition the mode has, every
// rotation and index selection: the packed block decodes (texproc's decoder,
// which matches Pillow's on random blocks) to the texels the equations give,
// whatever indices the anchors hold (packing swaps endpoints to clear their
// top bits).
TEST(Bc7Encode, EveryModeAndPartitionPacksWhatTheDecoderReads) {
  std::mt19937 rng(7);
  int checked = 0;
  for (int mode = 0; mode < 8; ++mode) {
    const bptc::Bc7Mode& M = bptc::kBc7Modes[mode];
    const int partitions = 1 << M.partition_bits;
    for (int part = 0; part < partitions; ++part)
      for (int rot = 0; rot < (M.rotation_bits ? 4 : 1); ++rot)
        for (int isel = 0; isel < (M.index_selection_bits ? 2 : 1); ++isel) {
          bc7::Choice c;
          c.mode = mode;
          c.partition = part;
          c.rotation = rot;
          c.index_selection = isel;
          for (int s = 0; s < M.subsets; ++s)
            for (int k = 0; k < 2; ++k) {
              for (int ch = 0; ch < 4; ++ch) {
                const int bits = ch < 3 ? M.color_bits : M.alpha_bits;
                c.code[s][k][ch] = bits ? int(rng() % (1u << bits)) : 0;
              }
              c.pbit[s][k] = M.endpoint_pbits ? int(rng() & 1) : 0;
            }
          if (M.shared_pbits)
            for (int s = 0; s < M.subsets; ++s) c.pbit[s][1] = c.pbit[s][0] = int(rng() & 1);
          const bool swap = mode == 4 && isel;
          const int cbits = swap ? M.index2_bits : M.index_bits, abits = swap ? M.index_bits : M.index2_bits;
          for (int i = 0; i < 16; ++i) {
            c.color_index[i] = std::uint8_t(rng() % (1u << cbits));
            c.alpha_index[i] = M.index2_bits ? std::uint8_t(rng() % (1u << abits)) : 0;
          }
          std::uint8_t block[16], want[16][4], got[16][4];
          bc7::pack_block(c, block);
          expected_texels(c, want);
          bc::decode_bc7(block, got);
          ASSERT_EQ(0, std::memcmp(want, got, sizeof want))
              << "mode " << mode << " partition " << part << " rotation " << rot << " isel " << isel;
          ++checked;
        }
  }
  EXPECT_EQ(checked, 16 + 64 + 64 + 64 + 8 + 4 + 1 + 64);
}

// The SIMD packer against the reference, block by block: batches of random
// choices, each lane its own mode, partition, rotation, index selection and
// indices (some lanes one colour), whole and cut short, on every target.
TEST(Bc7Encode, SimdPackerGivesTheReferenceBytes) {
  std::mt19937 rng(19);
  for (int batch = 0; batch < 400; ++batch) {
    bc7::LaneChoices t{};
    for (int k = 0; k < bc7::LaneChoices::N; ++k) {
      const int mode = int(rng() % 8);
      const bptc::Bc7Mode& M = bptc::kBc7Modes[mode];
      t.solid[k] = rng() % 8 == 0;
      for (int ch = 0; ch < 4; ++ch) t.x0[ch][k] = int(rng() & 255);
      t.mode[k] = mode;
      t.partition[k] = int(rng() % (1u << M.partition_bits));
      t.rotation[k] = M.rotation_bits ? int(rng() % 4) : 0;
      t.isel[k] = M.index_selection_bits ? int(rng() & 1) : 0;
      for (int s = 0; s < 3; ++s)
        for (int e = 0; e < 2; ++e) {
          for (int ch = 0; ch < 4; ++ch) {
            const int bits = ch < 3 ? M.color_bits : M.alpha_bits;
            t.code[s][e][ch][k] = s < M.subsets && bits ? int(rng() % (1u << bits)) : 0;
          }
          t.pbit[s][e][k] = s < M.subsets && (M.endpoint_pbits || M.shared_pbits) ? int(rng() & 1) : 0;
        }
      if (M.shared_pbits)
        for (int s = 0; s < M.subsets; ++s) t.pbit[s][1][k] = t.pbit[s][0][k];
      const bool swap = mode == 4 && t.isel[k];
      const int cbits = swap ? M.index2_bits : M.index_bits, abits = swap ? M.index_bits : M.index2_bits;
      for (int i = 0; i < 16; ++i) {
        t.color_index[i][k] = int(rng() % (1u << cbits));
        t.alpha_index[i][k] = M.index2_bits ? int(rng() % (1u << abits)) : 0;
      }
    }
    const int count = batch % 4 == 3 ? 1 + int(rng() % bc7::LaneChoices::N) : bc7::LaneChoices::N;
    std::vector<std::uint8_t> want(16 * bc7::LaneChoices::N), got(want.size());
    bc7::pack_lanes(t, count, reinterpret_cast<std::uint8_t(*)[16]>(want.data()));
    expect_same_on_every_target(
        [&] {
          std::fill(got.begin(), got.end(), 0);
          bc7::pack_lanes_simd(t, count, reinterpret_cast<std::uint8_t(*)[16]>(got.data()));
          return got;
        },
        "batch " + std::to_string(batch));
    ASSERT_EQ(got, want) << "batch " << batch;
  }
}

// One colour is exact in BC7 (mode 5 at weight 21 reaches every 8-bit value,
// found exhaustively here; alpha's endpoints are 8-bit), and the encoder
// gets it at every level, whatever the value.
TEST(Bc7Encode, OneColourBlocksAreExact) {
  for (int v = 0; v < 256; ++v) {
    const bc7::SolidPair& p = bc7::solid5(v);
    const int got = bptc::interpolate(bc7::expand(p.e0, 7, -1), bc7::expand(p.e1, 7, -1), 21);
    ASSERT_EQ(got, v);
  }
  std::mt19937 rng(3);
  for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max})
    for (int n = 0; n < 64; ++n) {
      Image img(4, 4, 4, PixelType::u8);
      std::uint8_t px[4];
      for (auto& c : px) c = std::uint8_t(n < 4 ? (n & 1) * 255 : rng() & 255);
      for (int i = 0; i < 16; ++i) std::memcpy(img.row<std::uint8_t>(i / 4) + 4 * (i % 4), px, 4);
      EXPECT_EQ(rgba_error(img, compress_image(img.view(), TexelFormat::bc7_unorm, q)), 0.0)
          << to_string(q) << " " << n;
    }
}

// Opaque images keep alpha 255 (mode 6's p-bits are forced to 1; the alpha
// modes are never tried); an image with alpha is not held to that.
TEST(Bc7Encode, OpaqueImagesNeverGetAlphaBelow255) {
  const Image noise = random_image(64, 32, 4, PixelType::u8, 11);
  Image opaque = noise;
  for (int y = 0; y < opaque.height(); ++y)
    for (int x = 0; x < opaque.width(); ++x) opaque.row<std::uint8_t>(y)[4 * x + 3] = 255;
  for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max}) {
    const Image d = decompress_image(compress_image(opaque.view(), TexelFormat::bc7_unorm, q), 64, 32,
                                     TexelFormat::bc7_unorm, PixelType::u8);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x) ASSERT_EQ(d.row<const std::uint8_t>(y)[4 * x + 3], 255) << to_string(q);
  }
}

// On corpus crops (a photo, an albedo, a normal map, cutouts with alpha):
// every level's error is no larger than the level below's, the SIMD lanes
// give the scalar reference's bytes on every target (max on a strip), and 1
// and 2 threads give the same bytes.
TEST(Bc7Encode, LevelsOrderAndSimdMatchesScalarOnCorpusCrops) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  struct Source {
    const char* file;
    bool opaque;
  };
  for (const Source& s :
       {Source{"photo/skimage_astronaut_512.png", true}, Source{"albedo_srgb/colobot_desert4.png", true},
        Source{"normal_ts/ufoai_rock017_nm_alphaheight.png", true}, Source{"alpha/ufoai_fence_512x256.png", false},
        Source{"alpha/trigger_palm_tree2_1000.png", false}}) {
    const Image src = read_image(corpus_dir() + "/" + s.file);
    const Image crop =
        crop_rgba8(src, 100, 100, 72, 40, s.opaque);  // 18 blocks a row: batches of 16 that cross rows, and a short one
    double last = INFINITY;
    for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
      const auto blocks = compress_image(crop.view(), TexelFormat::bc7_unorm, q);
      const double e = rgba_error(crop, blocks);
      EXPECT_LE(e, last) << s.file << " " << to_string(q);
      last = e;
      expect_same_on_every_target([&] { return compress_image(crop.view(), TexelFormat::bc7_unorm, q); },
                                  std::string(s.file) + " " + to_string(q));
      EXPECT_EQ(with_threads(1, [&] { return compress_image(crop.view(), TexelFormat::bc7_unorm, q); }),
                with_threads(2, [&] { return compress_image(crop.view(), TexelFormat::bc7_unorm, q); }))
          << s.file << " " << to_string(q);
    }
    // max (the endpoint steps' widest use) on a strip of ten blocks: SIMD as scalar.
    const Image strip = crop_rgba8(src, 100, 100, 40, 4, s.opaque);
    expect_same_on_every_target([&] { return compress_image(strip.view(), TexelFormat::bc7_unorm, Quality::max); },
                                std::string(s.file) + " max");
  }
}

// The fit's knobs in rows the levels do not use (joint quantization, two
// to four seeds, the winner's seeds with and without its steps, beside the
// p-bit search, the neighbouring-index check and the candidates' steps),
// through bc7_encode_lanes on corpus blocks with and without alpha: SIMD
// gives the scalar reference's bytes on every target.
TEST(Bc7Encode, FitKnobsOffTheLevelsSimdMatchesScalar) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Bc7Level rows[] = {
      {4, false, 64, 1, 1, false, true, false, 1, false, 0, 1, false, false, false, true, 1, 1},
      {4, false, 64, 1, 1, false, true, false, 1, false, 0, 0, false, false, false, false, 1, 3},
      {2, true, 64, 2, 4, true, true, true, 2, true, 1, 1, true, true, true, true, 4, 4},
      {6, false, 64, 2, 4, true, true, true, 1, false, 0, 2, true, false, true, true, 3, 4},
  };
  for (const char* file : {"photo/skimage_astronaut_512.png", "alpha/ufoai_fence_512x256.png"}) {
    const Image crop = crop_rgba8(read_image(corpus_dir() + "/" + file), 96, 96, 80, 12, false);  // 60 blocks
    const int bw = crop.width() / 4, count = bw * crop.height() / 4;
    std::vector<Bc7Texels> texel((count + kBc7Batch - 1) / kBc7Batch);
    for (int b = 0; b < count; ++b)
      for (int i = 0; i < 16; ++i) {
        const std::uint8_t* p = crop.row<const std::uint8_t>(b / bw * 4 + i / 4) + 4 * (b % bw * 4 + i % 4);
        texel[b / kBc7Batch][i][b % kBc7Batch] =
            std::uint32_t(p[0]) | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24;
      }
    for (const Bc7Level& level : rows)
      expect_same_on_every_target(
          [&] {
            std::vector<std::uint8_t> out(16 * std::size_t(count));
            bc7_encode_lanes(texel.data(), count, level, reinterpret_cast<std::uint8_t(*)[16]>(out.data()));
            return out;
          },
          std::string(file) + " seeds " + std::to_string(level.seeds) + "/" + std::to_string(level.winner_seeds));
  }
}

// BC7 against BC1 on the same opaque crop: more than 3 dB better at `fast`
// (BC1 has one 4-colour line a block at 5:6:5; on whole images the gap is
// about 8 dB), and sRGB is the same search on the stored values.
TEST(Bc7Encode, BeatsBc1AndSrgbIsTheSameBlocks) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const Image crop =
      crop_rgba8(read_image(corpus_dir() + "/photo/skimage_astronaut_512.png"), 128, 128, 128, 128, true);
  const auto bc7 = compress_image(crop.view(), TexelFormat::bc7_unorm, Quality::fast);
  const auto bc1 = compress_image(crop.view(), TexelFormat::bc1_rgb_unorm, Quality::high);
  const Image d1 = decompress_image(bc1, 128, 128, TexelFormat::bc1_rgb_unorm, PixelType::u8);
  double se1 = 0.0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 4 * 128; ++x) {
      const double e = double(crop.row<const std::uint8_t>(y)[x]) - double(d1.row<const std::uint8_t>(y)[x]);
      se1 += e * e;
    }
  EXPECT_GT(10.0 * std::log10(se1 / rgba_error(crop, bc7)), 3.0);
  EXPECT_EQ(bc7, compress_image(crop.view(), TexelFormat::bc7_srgb, Quality::fast));
}
