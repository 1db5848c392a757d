#include "container/format_names.h"

namespace texproc {

std::string vk_format_name(std::uint32_t vk) {
  switch (vk) {
    case 0: return "UNDEFINED";
    case 143: return "BC6H_UFLOAT_BLOCK";
    case 144: return "BC6H_SFLOAT_BLOCK";
    case 145: return "BC7_UNORM_BLOCK";
    case 146: return "BC7_SRGB_BLOCK";
    default: break;
  }
  // ASTC: 157 (4x4 UNORM) to 184 (12x12 SRGB), UNORM and SRGB alternating; SFLOAT from 1000066000.
  static const char* kFootprints[] = {"4x4", "5x4", "5x5", "6x5", "6x6", "8x5", "8x6", "8x8", "10x5", "10x6",
                                      "10x8", "10x10", "12x10", "12x12"};
  if (vk >= 157 && vk <= 184) {
    return std::string("ASTC_") + kFootprints[(vk - 157) / 2] + ((vk - 157) % 2 ? "_SRGB_BLOCK" : "_UNORM_BLOCK");
  }
  if (vk >= 1000066000u && vk <= 1000066013u) return std::string("ASTC_") + kFootprints[vk - 1000066000u] + "_SFLOAT_BLOCK";
  if (vk >= 1000054000u && vk <= 1000054007u) return "PVRTC (IMG)";
  return "";
}

std::string dxgi_format_name(std::uint32_t dxgi) {
  switch (dxgi) {
    case 94: return "BC6H_TYPELESS";
    case 95: return "BC6H_UF16";
    case 96: return "BC6H_SF16";
    case 97: return "BC7_TYPELESS";
    case 98: return "BC7_UNORM";
    case 99: return "BC7_UNORM_SRGB";
    case 2: return "R32G32B32A32_TYPELESS";
    case 10: return "R16G16B16A16_FLOAT";
    case 87: return "B8G8R8A8_UNORM";
    default: return "";
  }
}

}  // namespace texproc
