// The streamed chain (levels filtered together, a few rows held) against
// whole float levels filtered one after the other: the same bytes for every
// filter, wrap, size, channel count, type and thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <mutex>
#include <set>

#include "mip/chain_rows.h"
#include "support/filters.h"
#include "support/images.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

namespace {

::testing::AssertionResult same_chains(const MipChain& a, const MipChain& b) {
  if (a.levels.size() != b.levels.size()) {
    return ::testing::AssertionFailure() << a.levels.size() << " levels against " << b.levels.size();
  }
  for (std::size_t l = 0; l < a.levels.size(); ++l) {
    const Image& x = a.levels[l];
    const Image& y = b.levels[l];
    if (x.width() != y.width() || x.height() != y.height() || x.type() != y.type() ||
        std::memcmp(x.data(), y.data(), x.byte_size()) != 0) {
      return ::testing::AssertionFailure() << "level " << l << " differs";
    }
  }
  if (a.color_space != b.color_space) return ::testing::AssertionFailure() << "color spaces differ";
  return ::testing::AssertionSuccess();
}

}  // namespace

TEST(MipCascade, SameBytesAsWholeLevelsForEveryFilterWrapAndSize) {
  const int sizes[][2] = {{1, 1}, {1, 9}, {9, 1}, {3, 5}, {5, 300}, {257, 131}, {64, 64}, {200, 3}};
  int cases = 0;
  for (const auto& wh : sizes) {
    for (int channels = 1; channels <= 4; ++channels) {
      const PixelType type = channels == 3 ? PixelType::u16 : channels == 2 ? PixelType::f32 : PixelType::u8;
      const Image img = random_image(wh[0], wh[1], channels, type, unsigned(wh[0] * 7 + wh[1] + channels));
      for (FilterKind k : kAllFilters) {
        for (WrapMode w : kAllWraps) {
          MipOptions o;
          o.filter.kind = k;
          o.wrap = w;
          o.normal_map = channels >= 3 && k == FilterKind::kaiser;
          SCOPED_TRACE(std::to_string(wh[0]) + "x" + std::to_string(wh[1]) + " channels " + std::to_string(channels) +
                       " " + to_string(k) + " wrap " + std::to_string(int(w)));
          EXPECT_TRUE(same_chains(generate_mips(img.view(), o), detail::generate_mips_whole_levels(img.view(), o)));
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 8 * 4 * 6 * 3);
}

TEST(MipCascade, SameBytesWithOutputConversionsAndFewerLevels) {
  const Image img = random_image(301, 97, 4, PixelType::u8, 5);
  MipOptions o;
  o.output_type = PixelType::f32;
  EXPECT_TRUE(same_chains(generate_mips(img.view(), o), detail::generate_mips_whole_levels(img.view(), o)));
  o = MipOptions{};
  o.premultiplied_alpha = false;
  o.max_levels = 3;
  EXPECT_TRUE(same_chains(generate_mips(img.view(), o), detail::generate_mips_whole_levels(img.view(), o)));
  o = MipOptions{};
  o.output_type = PixelType::u16;
  o.min_size = 8;
  o.color_space = "linear";
  EXPECT_TRUE(same_chains(generate_mips(img.view(), o), detail::generate_mips_whole_levels(img.view(), o)));
}

// Many waves (the wave grows with the thread count): the same bytes on 1,
// 2 and 5 threads, with and without the SIMD kernels.
TEST(MipCascade, SameBytesForAnyThreadCountOverManyWaves) {
  const Image img = random_image(97, 2600, 4, PixelType::u8, 9);
  for (WrapMode w : kAllWraps) {
    MipOptions o;
    o.filter.kind = FilterKind::lanczos3;
    o.wrap = w;
    const MipChain reference = detail::generate_mips_whole_levels(img.view(), o);
    for (int threads : {1, 2, 5}) {
      ThreadLimit limit(threads);
      EXPECT_TRUE(same_chains(generate_mips(img.view(), o), reference)) << threads << " threads";
    }
    ScalarKernels scalar_only;
    EXPECT_TRUE(same_chains(generate_mips(img.view(), o), reference)) << "scalar";
  }
}

// A sink hears each row of each level 1.. once, after begin, and the rows
// it is given are generate_mips's.
TEST(MipCascade, SinkGetsEachRowOnce) {
  const Image img = random_image(123, 77, 3, PixelType::u8, 3);
  struct Recorder final : MipRowSink {
    std::vector<Image> levels;
    std::mutex m;
    std::set<std::pair<int, int>> asked, done;
    int begun = 0;
    int width = 0, height = 0;
    void begin(int n, PixelType type, int channels) override {
      ++begun;
      for (int l = 0; l < n; ++l) {
        levels.emplace_back(mip_level_dim(width, l), mip_level_dim(height, l), channels, type);
      }
    }
    void* row(int level, int y) override {
      std::lock_guard<std::mutex> lock(m);
      EXPECT_TRUE(asked.insert({level, y}).second) << "row " << y << " of level " << level << " asked twice";
      return levels[level].row<void>(y);
    }
    void row_done(int level, int y) override {
      std::lock_guard<std::mutex> lock(m);
      EXPECT_TRUE(asked.count({level, y}));
      EXPECT_TRUE(done.insert({level, y}).second);
    }
  } sink;
  sink.width = img.width();
  sink.height = img.height();
  MipOptions o;
  o.wrap = WrapMode::repeat;
  const MipChain info = generate_mips_rows(img.view(), o, sink);
  EXPECT_TRUE(info.levels.empty());
  EXPECT_EQ(sink.begun, 1);
  const MipChain whole = generate_mips(img.view(), o);
  ASSERT_EQ(sink.levels.size(), whole.levels.size());
  std::size_t rows = 0;
  for (std::size_t l = 1; l < whole.levels.size(); ++l) {
    rows += std::size_t(whole.levels[l].height());
    EXPECT_EQ(std::memcmp(sink.levels[l].data(), whole.levels[l].data(), whole.levels[l].byte_size()), 0) << l;
  }
  EXPECT_EQ(sink.asked.size(), rows);
  EXPECT_EQ(sink.done.size(), rows);
  EXPECT_EQ(info.color_space, whole.color_space);
}

// With alpha coverage the rows come from whole levels, and still once each.
TEST(MipCascade, CoverageStreamsTheSameRows) {
  const Image img = random_image(90, 60, 4, PixelType::u8, 4);
  MipOptions o;
  o.alpha_coverage_ref = 0.5f;
  struct Into final : MipRowSink {
    std::vector<Image>* levels = nullptr;
    void* row(int level, int y) override { return (*levels)[level].row<void>(y); }
  } sink;
  MipChain expected = generate_mips(img.view(), o);
  std::vector<Image> levels;
  for (const Image& l : expected.levels) levels.emplace_back(l.width(), l.height(), l.channels(), l.type());
  sink.levels = &levels;
  const MipChain info = generate_mips_rows(img.view(), o, sink);
  EXPECT_EQ(info.alpha_scale, expected.alpha_scale);
  for (std::size_t l = 1; l < levels.size(); ++l) {
    EXPECT_EQ(std::memcmp(levels[l].data(), expected.levels[l].data(), levels[l].byte_size()), 0) << l;
  }
}
