// texproc cubemap's writers: cube textures (plain or block-compressed,
// with each level's error), images and faces, spherical harmonics.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "common.h"
#include "cubemap_cli.h"
#include "json.h"
#include "texproc/color.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/texture.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc::cli::cube_cli {

// The texel format a cube texture gets: --format, else rgba16f for float
// input and for IBL maps, rgba8 (sRGB when the input was) otherwise.
TexelFormat cube_format(const CubemapArgs& a, const Source& s, bool lighting) {
  if (is_block_format(a.format)) return block_format_for(a.format, s.srgb());
  if (a.format == "rgba32f") return TexelFormat::rgba32_float;
  if (a.format == "rgba16f" || (a.format.empty() && (s.hdr || lighting))) return TexelFormat::rgba16_float;
  return s.srgb() ? TexelFormat::rgba8_srgb : TexelFormat::rgba8_unorm;
}

namespace {

// The largest colour value, for the clipping warning.
float peak_value(const Cubemap& c) {
  float peak = 0;
  for (const CubeLevel& l : c.levels)
    for (const Image& f : l.faces) {
      const float* p = f.row<float>(0);
      for (std::size_t k = 0; k < std::size_t(l.size) * l.size * 4; ++k)
        if (k % 4 != 3) peak = std::max(peak, p[k]);
    }
  return peak;
}

void warn_if_clipped(const std::string& input, const std::string& output, const Cubemap& c, TexelFormat format,
                     std::vector<std::string>& w) {
  const float peak = peak_value(c);
  if (peak > 1.0f) {
    std::ostringstream m;
    m << input << ": values up to " << peak << " are clipped to 1 in " << output << " (" << format_info(format).name
      << "); --format rgba16f, bc6h or astc-WxH-hdr, or an .exr output keeps them";
    w.push_back(m.str());
  }
}

// Writes the cube texture; for a block format, returns each level's error (level_errors).
std::vector<double> write_cube(const CubemapArgs& a, const Source& s, const Cubemap& c, const std::string& output,
                               bool lighting, std::vector<std::string>& warnings) {
  const TexelFormat format = cube_format(a, s, lighting);
  const FormatInfo& info = format_info(format);
  if (!info.is_float) warn_if_clipped(s.input, output, c, format, warnings);
  const ColorSpace out_space = info.srgb ? ColorSpace::srgb() : ColorSpace::linear();
  std::vector<std::vector<Image>> chains(6);
  for (const CubeLevel& l : c.levels)
    for (int f = 0; f < 6; ++f) {
      chains[f].push_back(info.is_float ? from_linear_rgba(l.faces[f].view(), ColorSpace::linear(), 4, PixelType::f32)
                                        : from_linear_rgba(l.faces[f].view(), out_space, 4, PixelType::u8));
    }
  if (!info.compressed) {
    write_texture(output,
                  texture_from_surfaces(std::move(chains), {.faces = 6},
                                        {.srgb = info.srgb, .half = format == TexelFormat::rgba16_float}),
                  a.header, zstd_level_for(a.zstd, output));
    return {};
  }
  const Texture t = compress_texture(chains, {.faces = 6}, format, a.q);
  write_texture(output, t, a.header, zstd_level_for(a.zstd, output));
  return level_errors(chains, t);
}

bool any_above_one(const std::vector<Image>& levels) {
  for (const Image& l : levels)
    for (int y = 0; y < l.height(); ++y) {
      const float* row = l.row<float>(y);
      for (int x = 0; x < l.width(); ++x)
        if (row[4 * x] > 1.0f || row[4 * x + 1] > 1.0f || row[4 * x + 2] > 1.0f) return true;
    }
  return false;
}

// Images in a file: float to .exr/.hdr/.tif (half in EXR), bytes elsewhere;
// several levels go into one MIP-mapped .exr or .tif.
void write_images(const Source& s, const std::vector<Image>& levels, const std::string& output,
                  std::vector<std::string>& warnings) {
  const std::string ext = fs::path(output).extension().string();
  const bool keeps_float = ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm";
  const int channels = s.alpha ? 4 : 3;
  std::vector<Image> out;
  WriteOptions w = cli_write_options();
  if (keeps_float) {
    for (const Image& l : levels)
      out.push_back(from_linear_rgba(l.view(), ColorSpace::linear(), channels, PixelType::f32));
    w.half = ext == ".exr";
    w.color_space = "linear";
  } else {
    if (any_above_one(levels)) {
      warnings.push_back(s.input + ": values above 1 are clipped in " + output + " (8-bit); write .exr to keep them");
    }
    const ColorSpace space = s.srgb() ? ColorSpace::srgb() : ColorSpace::linear();
    for (const Image& l : levels) out.push_back(from_linear_rgba(l.view(), space, channels, PixelType::u8));
    w.color_space = s.srgb() ? "srgb" : "linear";
  }
  if (out.size() == 1) {
    write_image(output, out[0].view(), w);
  } else {
    write_mip_file(output, out, w);
  }
}

}  // namespace

// One cube map (every level it has) to the files files_for named; a
// block-compressed cube texture's level errors (write_cube).
std::vector<double> write_environment(const CubemapArgs& a, const Source& s, const Cubemap& c,
                                      const std::vector<std::string>& files, bool lighting,
                                      std::vector<std::string>& warnings) {
  const Target t = target_for(a, files[0]);
  if (t == Target::cube) return write_cube(a, s, c, files[0], lighting, warnings);
  if (t == Target::faces) {
    for (int f = 0; f < 6; ++f) {
      std::vector<Image> levels;
      for (const CubeLevel& l : c.levels) levels.push_back(l.faces[f]);
      write_images(s, levels, files[f], warnings);
    }
    return {};
  }
  std::vector<Image> images;
  for (int l = 0; l < int(c.levels.size()); ++l) {
    switch (t) {
      case Target::equirect: {
        const int w = a.equirect_width > 0 ? a.equirect_width : 4 * c.levels[0].size;
        images.push_back(cubemap_to_equirect(c, std::max(2, w >> l), l));
        break;
      }
      case Target::vcross:
        images.push_back(cubemap_to_layout(c, CubeLayout::cross_vertical, l));
        break;
      case Target::strip:
        images.push_back(cubemap_to_layout(c, CubeLayout::strip_horizontal, l));
        break;
      case Target::vstrip:
        images.push_back(cubemap_to_layout(c, CubeLayout::strip_vertical, l));
        break;
      default:
        images.push_back(cubemap_to_layout(c, CubeLayout::cross_horizontal, l));
        break;
    }
  }
  write_images(s, images, files[0], warnings);
  return {};
}

void write_sh(const std::string& path, const SphericalHarmonics9& sh) {
  static const char* kNames[9] = {"Y00", "Y1-1", "Y10", "Y11", "Y2-2", "Y2-1", "Y20", "Y21", "Y22"};
  static constexpr double kBand[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};
  Json::Value order(Json::arrayValue), radiance(Json::arrayValue), irradiance(Json::arrayValue);
  for (int k = 0; k < 9; ++k) {
    Json::Value r(Json::arrayValue), e(Json::arrayValue);
    for (int c = 0; c < 3; ++c) {
      r.append(sh.radiance[k][c]);
      e.append(kBand[k] * sh.radiance[k][c]);
    }
    order.append(kNames[k]);
    radiance.append(r);
    irradiance.append(e);
  }
  Json::Value j(Json::objectValue);
  j["basis"] = "real spherical harmonics, Ramamoorthi and Hanrahan 2001, texproc axes (docs/cubemap.md)";
  j["order"] = order;
  j["radiance"] = radiance;
  j["irradiance_over_pi"] = irradiance;
  write_file_atomic(path, to_json(j, kExactDigits) + "\n");
}

}  // namespace texproc::cli::cube_cli
