// block_format_for and exact_block_format (texture.h): the names
// `texproc compress --format` reads, families and other tools' names.
#include <cctype>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include "texproc/error.h"
#include "texproc/texture.h"

namespace texproc {

std::optional<TexelFormat> exact_block_format(std::string_view f) {
  try {
    const TexelFormat t = parse_texel_format(f);
    if (format_info(t).compressed) return t;
  } catch (const Error&) {
  }
  return std::nullopt;
}

// A family's UNORM (SNORM, float) and sRGB formats: BC1-BC3, BC7, ETC2 have
// both; BC4/BC5, EAC and BC6H hold data and have one.
TexelFormat block_format_for(std::string_view f, bool srgb) {
  if (const auto t = exact_block_format(f)) return *t;
  using F = TexelFormat;
  static const std::map<std::string, std::pair<F, F>> k = {{"bc1", {F::bc1_rgb_unorm, F::bc1_rgb_srgb}},
                                                           {"bc1a", {F::bc1_rgba_unorm, F::bc1_rgba_srgb}},
                                                           {"bc2", {F::bc2_unorm, F::bc2_srgb}},
                                                           {"bc3", {F::bc3_unorm, F::bc3_srgb}},
                                                           {"bc4", {F::bc4_unorm, F::bc4_unorm}},
                                                           {"bc4s", {F::bc4_snorm, F::bc4_snorm}},
                                                           {"bc5", {F::bc5_unorm, F::bc5_unorm}},
                                                           {"bc5s", {F::bc5_snorm, F::bc5_snorm}},
                                                           {"bc7", {F::bc7_unorm, F::bc7_srgb}},
                                                           {"bc6h", {F::bc6h_ufloat, F::bc6h_ufloat}},
                                                           {"bc6hs", {F::bc6h_sfloat, F::bc6h_sfloat}},
                                                           {"etc1", {F::etc1_rgb, F::etc1_rgb}},
                                                           {"etc2", {F::etc2_rgb_unorm, F::etc2_rgb_srgb}},
                                                           {"etc2a1", {F::etc2_rgba1_unorm, F::etc2_rgba1_srgb}},
                                                           {"etc2a", {F::etc2_rgba8_unorm, F::etc2_rgba8_srgb}},
                                                           {"eac-r11", {F::eac_r11_unorm, F::eac_r11_unorm}},
                                                           {"eac-r11s", {F::eac_r11_snorm, F::eac_r11_snorm}},
                                                           {"eac-rg11", {F::eac_rg11_unorm, F::eac_rg11_unorm}},
                                                           {"eac-rg11s", {F::eac_rg11_snorm, F::eac_rg11_snorm}}};
  // The names other tools use (texconv, nvcompress, Compressonator), in any case.
  static const std::map<std::string, std::string> aliases = {
      {"dxt1", "bc1"},       {"dxt1a", "bc1a"},      {"dxt3", "bc2"},        {"dxt5", "bc3"},
      {"ati1", "bc4"},       {"bc4u", "bc4"},        {"ati2", "bc5"},        {"bc5u", "bc5"},
      {"3dc", "bc5"},        {"bc7u", "bc7"},        {"bc6hu", "bc6h"},      {"bc6h_uf16", "bc6h"},
      {"bc6h-uf16", "bc6h"}, {"bc6h_sf16", "bc6hs"}, {"bc6h-sf16", "bc6hs"}, {"bc6h_sf", "bc6hs"},
      {"etc2a8", "etc2a"},   {"etc2-rgba", "etc2a"}, {"r11", "eac-r11"},     {"rg11", "eac-rg11"}};
  std::string name(f);
  for (auto& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (auto al = aliases.find(name); al != aliases.end()) name = al->second;
  auto it = k.find(name);
  if (it != k.end()) return srgb ? it->second.second : it->second.first;
  // ASTC: astc-WxH (LDR: sRGB for colour, UNORM with --linear) and
  // astc-WxH-hdr (SFLOAT); astc_6x6 and astc6x6 are read the same.
  if (name.rfind("astc", 0) == 0) {
    std::string rest = name.substr(4);
    if (!rest.empty() && (rest[0] == '-' || rest[0] == '_')) rest.erase(0, 1);
    bool hdr = false;
    for (const char* suffix : {"-hdr", "_hdr"}) {
      if (rest.size() > 4 && rest.compare(rest.size() - 4, 4, suffix) == 0) {
        hdr = true;
        rest.resize(rest.size() - 4);
      }
    }
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(rest.c_str(), "%dx%d%c", &w, &h, &tail) == 2) {
      try {
        return astc_format(w, h, srgb && !hdr, hdr);
      } catch (const Error&) {  // the message below lists the footprints
      }
    }
  }
  throw Error(ErrorCode::bad_arguments,
              "unknown --format '" + std::string(f) +
                  "' (valid: bc1, bc1a, bc2, bc3, bc4, bc4s, bc5, bc5s, bc7, bc6h, bc6hs, etc1, etc2, etc2a1, "
                  "etc2a, eac-r11, eac-r11s, eac-rg11, eac-rg11s, astc-WxH and astc-WxH-hdr "
                  "for the footprints 4x4, 5x4, 5x5, 6x5, 6x6, 8x5, 8x6, 8x8, 10x5, 10x6, "
                  "10x8, 10x10, 12x10, 12x12; or a full name as info prints it, DXGI's or "
                  "Vulkan's: bc7_srgb, BC7_UNORM_SRGB, VK_FORMAT_BC7_SRGB_BLOCK)");
}

}  // namespace texproc
