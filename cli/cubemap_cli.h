// What texproc cubemap's steps share: its options, the files one input
// writes, the cube as read, and the writers (cubemap_outputs.cpp).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "batch.h"
#include "texproc/block_encode.h"
#include "texproc/container.h"
#include "texproc/cubemap.h"
#include "texproc/image_io.h"

namespace texproc::cli::cube_cli {

inline constexpr const char* kFaceNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};

enum class Target { automatic, cube, cross, vcross, strip, vstrip, equirect, faces };
enum class Ibl { none, specular, irradiance, both };

struct Plan {
  std::vector<std::string> main;        // the environment (or IBL map) files
  std::vector<std::string> irradiance;  // --ibl both
  std::string sh, preview;
  std::vector<std::string> all() const {
    std::vector<std::string> v = main;
    v.insert(v.end(), irradiance.begin(), irradiance.end());
    for (const std::string* s : {&sh, &preview})
      if (!s->empty()) v.push_back(*s);
    return v;
  }
};

struct CubemapArgs {
  BatchInputs io;
  std::vector<std::string> faces;
  std::string layout = "auto", to = "auto", format, color_space, flip = "none", ibl = "none";
  std::string irradiance_path, sh_path, preview_path, dds_header = "auto", quality = "normal";
  bool linear = false, mips = false, report = false;
  int size = 0, levels = 0, equirect_width = 0, irradiance_size = 32, samples = 512, zstd = 0;
  float exposure = 1.0f;
  // From the options, once (validate):
  Target target = Target::automatic;
  Ibl mode = Ibl::none;
  CubeFlip flip_axis = CubeFlip::none;
  DdsHeader header = DdsHeader::automatic;
  bool output_is_folder = false;
  Quality q = Quality::normal;
  std::map<std::string, Plan> plans;  // by input, made before any file runs
};

// A block-compressed --format (bc6h, bc7, astc-6x6-hdr...), not a plain one.
inline bool is_block_format(const std::string& format) {
  return !format.empty() && format != "rgba8" && format != "rgba16f" && format != "rgba32f";
}

// The cube as read, and the file messages name (the +X face for --faces).
struct Source : CubemapSource {
  std::string input;
  bool srgb() const { return color_space.is_srgb(); }  // rgba8 outputs say so
};

// What -o holds for this output name.
Target target_for(const CubemapArgs& a, const std::string& output);

// The texel format a cube texture gets: --format, else rgba16f for float
// input and for IBL maps, rgba8 (sRGB when the input was) otherwise.
TexelFormat cube_format(const CubemapArgs& a, const Source& s, bool lighting);

// One cube map (every level it has) to the files files_for named; a
// block-compressed cube texture's level errors (level_errors).
std::vector<double> write_environment(const CubemapArgs& a, const Source& s, const Cubemap& c,
                                      const std::vector<std::string>& files, bool lighting,
                                      std::vector<std::string>& warnings);

// The nine spherical-harmonic coefficients as JSON.
void write_sh(const std::string& path, const SphericalHarmonics9& sh);

}  // namespace texproc::cli::cube_cli
