// What the block-compression benchmarks share: the corpus colour textures
// they encode, and RGB PSNR under texproc's decoders.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "texproc/block_decode.h"
#include "texproc/image_io.h"

namespace texproc::bench {

// Runs a shell command, its output discarded; its wall-clock seconds, or -1
// where it failed (whole-process comparisons with other tools).
inline double timed_command(const std::string& command) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::system((command + " >/dev/null 2>&1").c_str()) != 0) return -1.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// An RGBA8 crop (multiples of 4) of a corpus image's colour, alpha opaque.
inline Image color_crop(const std::string& corpus_path) {
  const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + corpus_path);
  const int w = src.width() / 4 * 4, h = src.height() / 4 * 4;
  Image img(w, h, 4, PixelType::u8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) img.set(x, y, c, c == 3 ? 1.0f : src.get(x, y, std::min(c, src.channels() - 1)));
  return img;
}

// RGBA8 crops of six corpus colour textures (1.4 MPix).
inline const std::vector<Image>& color_textures() {
  static const std::vector<Image> t = [] {
    std::vector<Image> out;
    for (const char* f :
         {"albedo_srgb/colobot_desert4.png", "albedo_srgb/ufoai_rock017.png", "photo/skimage_astronaut_512.png",
          "albedo_srgb/wz2100_terrain_tile10_128_palette.png", "photo/skimage_coffee_600x400.png",
          "albedo_srgb/stellarium_stein_mauerwerk_512_rgba_opaque.png"})
      out.push_back(color_crop(f));
    return out;
  }();
  return t;
}

// The corpus paths of every albedo and photo in MANIFEST.tsv (15 images,
// 17 MPix), in its order.
inline std::vector<std::string> corpus_color_paths() {
  std::vector<std::string> out;
  std::ifstream manifest(std::string(TEXPROC_CORPUS_DIR) + "/MANIFEST.tsv");
  std::string line;
  while (std::getline(manifest, line)) {
    const std::size_t tab = line.find('\t'), tab2 = line.find('\t', tab + 1);
    if (tab == std::string::npos || tab2 == std::string::npos) continue;
    const std::string category = line.substr(tab + 1, tab2 - tab - 1);
    if (category == "albedo_srgb" || category == "photo") out.push_back(line.substr(0, tab));
  }
  return out;
}

// 256x256 centred RGBA8 crops (alpha opaque) of corpus_color_paths()'s 15
// images: the BC7 benchmarks' setting (bench_bc7, bc7_sweep).
inline const std::vector<Image>& centred_crops() {
  static const std::vector<Image> c = [] {
    std::vector<Image> out;
    for (const std::string& f : corpus_color_paths()) {
      const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + f);
      const int w = std::min(256, src.width() / 4 * 4), h = std::min(256, src.height() / 4 * 4);
      const int x0 = (src.width() - w) / 2, y0 = (src.height() - h) / 2;
      Image img(w, h, 4, PixelType::u8);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int ch = 0; ch < 4; ++ch)
            img.set(x, y, ch, ch == 3 ? 1.0f : src.get(x0 + x, y0 + y, src.channels() < 3 ? 0 : ch));
      out.push_back(std::move(img));
    }
    return out;
  }();
  return c;
}

// The squared error over RGB of `blocks` (format f) against the RGBA8
// source, summed (benchmarks that pool images add these up).
inline double squared_error_rgb(const Image& src, TexelFormat f, const std::vector<std::uint8_t>& blocks) {
  const Image d = decompress_image(blocks, src.width(), src.height(), f, PixelType::u8);
  double se = 0;
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double e = double(d.row<std::uint8_t>(y)[d.channels() * x + c]) - src.row<std::uint8_t>(y)[4 * x + c];
        se += e * e;
      }
  return se;
}

// PSNR over RGB of `blocks` (format f) against the RGBA8 source.
inline double psnr_rgb(const Image& src, TexelFormat f, const std::vector<std::uint8_t>& blocks) {
  return 10 * std::log10(255.0 * 255.0 / (squared_error_rgb(src, f, blocks) / (3.0 * src.width() * src.height())));
}

}  // namespace texproc::bench
