// texproc_ocio: OpenColorIO behind the C boundary of ocio_module.h, in a
// module loaded on first use. Without $OCIO, texproc uses the small built-in
// config below (OCIO 2.1, as Debian 12 ships it, has no built-in configs of
// its own).
#include "image/ocio/ocio_module.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "texproc/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace texproc {
namespace {

// Reference space: linear Rec.709 primaries, D65 (scene_linear). Every other
// space says how to get to it. Matrices: XYZ(D65) to linear Rec.709 from
// IEC 61966-2-1; Display P3 to Rec.709 derived from the P3-D65 primaries.
constexpr const char* kBuiltinConfig = R"ocio(ocio_profile_version: 2.1
name: texproc-builtin
description: texproc built-in config (see docs/color.md)
roles:
  default: lin_rec709
  scene_linear: lin_rec709
  reference: lin_rec709
  data: raw
  color_picking: sRGB
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  sRGB:
    - !<View> {name: Raw, colorspace: raw}
colorspaces:
  - !<ColorSpace>
    name: lin_rec709
    aliases: [lin_srgb, "Linear Rec.709 (sRGB)"]
    family: linear
    encoding: scene-linear
  - !<ColorSpace>
    name: sRGB
    aliases: ["sRGB - Texture", srgb_tx, srgb_texture]
    encoding: sdr-video
    to_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}
  - !<ColorSpace>
    name: g22_rec709
    aliases: ["Gamma 2.2 Rec.709", gamma22]
    encoding: sdr-video
    to_scene_reference: !<ExponentTransform> {value: 2.2, style: pass_thru}
  - !<ColorSpace>
    name: g24_rec709
    aliases: ["Gamma 2.4 Rec.709", rec1886, gamma24]
    encoding: sdr-video
    to_scene_reference: !<ExponentTransform> {value: 2.4, style: pass_thru}
  - !<ColorSpace>
    name: ACEScg
    aliases: ["ACES - ACEScg", lin_ap1]
    family: linear
    encoding: scene-linear
    to_scene_reference: !<BuiltinTransform> {style: "UTILITY - ACES-AP1_to_LINEAR-REC709_BFD"}
  - !<ColorSpace>
    name: ACES2065-1
    aliases: ["ACES - ACES2065-1", lin_ap0]
    family: linear
    encoding: scene-linear
    to_scene_reference: !<GroupTransform>
      children:
        - !<BuiltinTransform> {style: "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"}
        - !<MatrixTransform> {matrix: [3.2409699419, -1.5373831776, -0.4986107603, 0, -0.9692436363, 1.8759675015, 0.0415550574, 0, 0.0556300797, -0.2039769589, 1.0569715142, 0, 0, 0, 0, 1]}
  - !<ColorSpace>
    name: ACEScct
    aliases: ["ACES - ACEScct", acescct_ap1]
    encoding: log
    to_scene_reference: !<GroupTransform>
      children:
        - !<BuiltinTransform> {style: "ACEScct_to_ACES2065-1"}
        - !<BuiltinTransform> {style: "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"}
        - !<MatrixTransform> {matrix: [3.2409699419, -1.5373831776, -0.4986107603, 0, -0.9692436363, 1.8759675015, 0.0415550574, 0, 0.0556300797, -0.2039769589, 1.0569715142, 0, 0, 0, 0, 1]}
  - !<ColorSpace>
    name: display_p3
    aliases: ["Display P3", srgb_p3]
    encoding: sdr-video
    to_scene_reference: !<GroupTransform>
      children:
        - !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}
        - !<MatrixTransform> {matrix: [1.2249401763, -0.2249404378, 0, 0, -0.0420569547, 1.0420571574, 0, 0, -0.0196375546, -0.0786360454, 1.0982736000, 0, 0, 0, 0, 1]}
  - !<ColorSpace>
    name: raw
    aliases: [Raw, "Utility - Raw", non-color]
    family: data
    isdata: true
)ocio";

struct ActiveConfig {
  OCIO::ConstConfigRcPtr config;
  std::string path;  // "" for the built-in one
};

const ActiveConfig& active_config() {
  static std::once_flag once;
  static ActiveConfig active;
  static std::string load_error;
  std::call_once(once, [] {
    try {
      const char* env = std::getenv("OCIO");
      if (env && *env) {
        active.path = env;
        active.config = OCIO::Config::CreateFromFile(env);
      } else {
        std::istringstream in(kBuiltinConfig);
        active.config = OCIO::Config::CreateFromStream(in);
      }
    } catch (const OCIO::Exception& e) {
      load_error = e.what();
      active.config.reset();
    }
  });
  if (!active.config) {
    throw Error(ErrorCode::invalid_file, std::string(std::getenv("OCIO") ? std::getenv("OCIO") : "<built-in>") +
                                             ": cannot load the OpenColorIO config: " + load_error);
  }
  return active;
}

class Transform {
 public:
  Transform(OCIO::ConstCPUProcessorRcPtr to, OCIO::ConstCPUProcessorRcPtr from)
      : to_(std::move(to)), from_(std::move(from)) {}
  void to_linear(float* pixels, int channels, int width) const { apply(*to_, pixels, channels, width); }
  void from_linear(float* pixels, int channels, int width) const { apply(*from_, pixels, channels, width); }

 private:
  static void apply(const OCIO::CPUProcessor& p, float* px, int channels, int width) {
    if (channels >= 3) {
      OCIO::PackedImageDesc desc(px, width, 1, channels);
      p.apply(desc);
      return;
    }
    // Gray (+alpha): through as R=G=B, keep G.
    for (int x = 0; x < width; ++x) {
      float rgb[3] = {px[x * channels], px[x * channels], px[x * channels]};
      p.applyRGB(rgb);
      px[x * channels] = rgb[1];
    }
  }

  OCIO::ConstCPUProcessorRcPtr to_, from_;
};

void copy_out(char* dst, size_t size, const std::string& s) {
  if (!dst || !size) return;
  const size_t n = std::min(size - 1, s.size());
  std::memcpy(dst, s.data(), n);
  dst[n] = '\0';
}

std::vector<std::string> space_names() {
  const auto& cfg = *active_config().config;
  std::vector<std::string> out;
  for (int i = 0; i < cfg.getNumColorSpaces(); ++i) out.emplace_back(cfg.getColorSpaceNameByIndex(i));
  return out;
}

void* create(const char* space_c, char* config_path, size_t path_size, int* code, char* err, size_t err_size) {
  const std::string space = space_c;
  try {
    const ActiveConfig& active = active_config();
    if (!active.config->getColorSpace(space.c_str())) {
      std::string valid = "linear, srgb";
      for (const auto& n : space_names()) valid += ", " + n;
      throw Error(ErrorCode::bad_arguments, "unknown color space '" + space + "' (valid: " + valid + ")");
    }
    try {
      auto to = active.config->getProcessor(space.c_str(), OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor();
      auto from = active.config->getProcessor(OCIO::ROLE_SCENE_LINEAR, space.c_str())->getDefaultCPUProcessor();
      copy_out(config_path, path_size, active.path);
      return new Transform(std::move(to), std::move(from));
    } catch (const OCIO::Exception& e) {
      throw Error(ErrorCode::bad_arguments,
                  "color space '" + space + "': OpenColorIO cannot convert it to scene_linear: " + e.what());
    }
  } catch (const Error& e) {
    *code = int(e.code());
    copy_out(err, err_size, e.what());
  } catch (const std::exception& e) {
    *code = int(ErrorCode::runtime);
    copy_out(err, err_size, e.what());
  }
  return nullptr;
}

void to_linear(const void* t, float* px, int channels, int width) {
  static_cast<const Transform*>(t)->to_linear(px, channels, width);
}
void from_linear(const void* t, float* px, int channels, int width) {
  static_cast<const Transform*>(t)->from_linear(px, channels, width);
}
void destroy(void* t) { delete static_cast<Transform*>(t); }

long names(char* out, size_t size, int* code, char* err, size_t err_size) {
  try {
    std::string all;
    for (const auto& n : space_names()) all += n + '\0';
    if (out && all.size() <= size) std::memcpy(out, all.data(), all.size());
    return long(all.size());
  } catch (const Error& e) {
    *code = int(e.code());
    copy_out(err, err_size, e.what());
  }
  return -1;
}

const TpOcioModule kModule = {TP_OCIO_MODULE_ABI, create, to_linear, from_linear, destroy, names};

}  // namespace
}  // namespace texproc

extern "C" __attribute__((visibility("default"))) const TpOcioModule* texproc_ocio_module(void) {
  return &texproc::kModule;
}
