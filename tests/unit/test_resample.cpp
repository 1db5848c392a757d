// Polyphase weights, wrap modes, and the SIMD passes against their scalar twins.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

#include "mip/resample.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

using namespace texproc;

namespace {
const FilterKind kAllFilters[] = {FilterKind::box,    FilterKind::triangle, FilterKind::gaussian,
                                  FilterKind::kaiser, FilterKind::lanczos3, FilterKind::mitchell};
}

TEST(Wrap, IndexMapping) {
  // clamp
  EXPECT_EQ(wrap_index(-3, 5, WrapMode::clamp), 0);
  EXPECT_EQ(wrap_index(7, 5, WrapMode::clamp), 4);
  // repeat: period n
  EXPECT_EQ(wrap_index(-1, 5, WrapMode::repeat), 4);
  EXPECT_EQ(wrap_index(-6, 5, WrapMode::repeat), 4);
  EXPECT_EQ(wrap_index(12, 5, WrapMode::repeat), 2);
  // mirror: ... 1 0 | 0 1 2 3 4 | 4 3 ...
  EXPECT_EQ(wrap_index(-1, 5, WrapMode::mirror), 0);
  EXPECT_EQ(wrap_index(-2, 5, WrapMode::mirror), 1);
  EXPECT_EQ(wrap_index(5, 5, WrapMode::mirror), 4);
  EXPECT_EQ(wrap_index(6, 5, WrapMode::mirror), 3);
  EXPECT_EQ(wrap_index(10, 5, WrapMode::mirror), 0);
  EXPECT_EQ(wrap_index(-3, 1, WrapMode::mirror), 0);
}

TEST(Filters, ParseListsValidNames) {
  EXPECT_EQ(parse_filter_kind("lanczos3"), FilterKind::lanczos3);
  try {
    parse_filter_kind("bicubic");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("valid: box, triangle, gaussian, kaiser, lanczos3, mitchell"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_wrap_mode("border"), Error);
}

TEST(Weights, IdentityWhenSizeUnchanged) {
  const AxisWeights w = compute_axis_weights(7, 7, Filter{});
  EXPECT_EQ(w.taps, 1);
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(w.first[i], i);
    EXPECT_EQ(w.weights[i], 1.0f);
  }
}

// Halving: texel i is centred at source 2i + 0.5; every filter here is
// symmetric, so the weights are a palindrome around that centre and sum to 1.
TEST(Weights, HalvingIsSymmetricAndNormalized) {
  for (FilterKind k : kAllFilters) {
    const AxisWeights w = compute_axis_weights(64, 32, Filter{k, 0.5f});
    for (int i = 0; i < 32; ++i) {
      const float* r = &w.weights[i * w.taps];
      EXPECT_NEAR(std::accumulate(r, r + w.taps, 0.0), 1.0, 1e-6) << to_string(k);
      const double centre = w.first[i] + (w.taps - 1) / 2.0;
      EXPECT_DOUBLE_EQ(centre, 2 * i + 0.5) << to_string(k);
      for (int t = 0; t < w.taps; ++t) EXPECT_NEAR(r[t], r[w.taps - 1 - t], 1e-7) << to_string(k);
    }
  }
  EXPECT_EQ(compute_axis_weights(64, 32, Filter{FilterKind::box}).taps, 2);
  EXPECT_EQ(compute_axis_weights(64, 32, Filter{FilterKind::triangle}).taps, 4);
  EXPECT_EQ(compute_axis_weights(64, 32, Filter{FilterKind::gaussian, 0.5f}).taps, 8);
}

// 5 -> 2 with a box: destination texel 0 covers source [0, 2.5), so texels
// 0 and 1 fully and texel 2 half: weights 1, 1, 0.5 over 2.5.
TEST(Weights, BoxOddSizeUsesExactCoverage) {
  const AxisWeights w = compute_axis_weights(5, 2, Filter{FilterKind::box});
  ASSERT_EQ(w.taps, 3);
  EXPECT_EQ(w.first[0], 0);
  EXPECT_FLOAT_EQ(w.weights[0], 0.4f);
  EXPECT_FLOAT_EQ(w.weights[1], 0.4f);
  EXPECT_FLOAT_EQ(w.weights[2], 0.2f);
  EXPECT_EQ(w.first[1], 2);
  EXPECT_FLOAT_EQ(w.weights[3], 0.2f);
  EXPECT_FLOAT_EQ(w.weights[4], 0.4f);
  EXPECT_FLOAT_EQ(w.weights[5], 0.4f);
  // 3 -> 1: all three texels equally.
  const AxisWeights w3 = compute_axis_weights(3, 1, Filter{FilterKind::box});
  ASSERT_EQ(w3.taps, 3);
  for (int t = 0; t < 3; ++t) EXPECT_FLOAT_EQ(w3.weights[t], 1.0f / 3.0f);
}

// Odd sizes keep the centre: 7 -> 3 has s = 7/3, texel 1 centred on source 3.
TEST(Weights, OddSizeIsNotShifted) {
  const AxisWeights w = compute_axis_weights(7, 3, Filter{FilterKind::gaussian, 0.5f});
  double centre = 0.0;
  for (int t = 0; t < w.taps; ++t) centre += w.weights[w.taps + t] * (w.first[1] + t);
  EXPECT_NEAR(centre, 3.0, 1e-6);
}

namespace {
// Runs `check` once for every SIMD target this CPU supports (and Highway
// compiled), then restores normal dispatch.
template <typename F>
void for_each_simd_target(F check) {
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    check();
  }
  hwy::SetSupportedTargetsForTest(0);
}
}  // namespace

TEST(SimdTwins, VerticalPassMatchesReferenceBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 2.0f);
  for (int taps : {1, 2, 3, 8, 13}) {
    for (int n : {1, 5, 16, 37, 1000}) {
      std::vector<std::vector<float>> rows(taps, std::vector<float>(n));
      std::vector<const float*> ptrs;
      for (auto& r : rows) {
        for (float& v : r) v = u(rng);
        ptrs.push_back(r.data());
      }
      std::vector<float> w(taps);
      for (float& v : w) v = u(rng);
      std::vector<float> expect(n), got(n);
      ref::vertical_pass(ptrs.data(), w.data(), taps, n, expect.data());
      for_each_simd_target([&] {
        std::fill(got.begin(), got.end(), -99.0f);
        vertical_pass(ptrs.data(), w.data(), taps, n, got.data());
        ASSERT_EQ(0, std::memcmp(expect.data(), got.data(), n * sizeof(float))) << taps << " " << n;
      });
    }
  }
}

TEST(SimdTwins, HorizontalPassMatchesReferenceBitForBit) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int channels = 1; channels <= 4; ++channels) {
    for (int src : {2, 9, 64, 301}) {
      for (FilterKind k : kAllFilters) {
        const int dst = std::max(1, src / 2);
        const AxisWeights w = compute_axis_weights(src, dst, Filter{k, 0.5f});
        std::vector<float> row((w.pad_before + src + w.pad_after) * channels);
        for (float& v : row) v = u(rng);
        const float* mid = row.data() + w.pad_before * channels;
        std::vector<float> expect(dst * channels), got(dst * channels);
        ref::horizontal_pass(mid, channels, w.first.data(), w.weights.data(), w.taps, dst, expect.data());
        for_each_simd_target([&] {
          horizontal_pass(mid, channels, w.first.data(), w.weights.data(), w.taps, dst, got.data());
          ASSERT_EQ(0, std::memcmp(expect.data(), got.data(), got.size() * sizeof(float)));
        });
      }
    }
  }
}

TEST(SimdTwins, ScalarKernelsNestAndEnd) {
  if (force_scalar()) GTEST_SKIP() << "TEXPROC_FORCE_SCALAR is set";
  {
    ScalarKernels outer;
    EXPECT_EQ(simd_target_name(), "scalar");
    {
      ScalarKernels inner;
      EXPECT_TRUE(force_scalar());
    }
    EXPECT_TRUE(force_scalar());  // the outer one still holds
  }
  EXPECT_FALSE(force_scalar());
  EXPECT_NE(simd_target_name(), "scalar");
}
