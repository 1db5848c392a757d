// Analytic test images and small helpers shared by the tests.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <unistd.h>

#include "texproc/image.h"

namespace texproc::test {

// A black/white one-texel checkerboard, 8-bit, `channels` channels (alpha 255).
inline Image checkerboard(int w, int h, int channels) {
  Image img(w, h, channels, PixelType::u8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        img.row<std::uint8_t>(y)[x * channels + c] =
            (channels == 2 || channels == 4) && c == channels - 1 ? 255 : ((x + y) & 1 ? 255 : 0);
  return img;
}

// Uniformly random texels of any type, reproducible from `seed`.
inline Image random_image(int w, int h, int channels, PixelType type, unsigned seed) {
  Image img(w, h, channels, type);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) img.set(x, y, c, u(rng));
  return img;
}

inline Image constant_image(int w, int h, int channels, PixelType type, const float* value) {
  Image img(w, h, channels, type);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) img.set(x, y, c, value[c]);
  return img;
}

inline std::string corpus_dir() { return TEXPROC_CORPUS_DIR; }
// A file's bytes ("" where it cannot be read).
inline std::string slurp_file(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}
inline bool have_corpus() { return std::filesystem::exists(corpus_dir() + "/MANIFEST.tsv"); }

// A fresh empty folder under the system temp folder.
inline std::string temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("texproc_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace texproc::test
