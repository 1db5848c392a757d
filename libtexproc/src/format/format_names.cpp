#include "format/format_names.h"

namespace texproc {

std::string vk_format_name(std::uint32_t vk) {
  switch (vk) {
    case 0:
      return "UNDEFINED";
    case 9:
      return "R8_UNORM";
    case 15:
      return "R8_SRGB";
    case 16:
      return "R8G8_UNORM";
    case 22:
      return "R8G8_SRGB";
    case 37:
      return "R8G8B8A8_UNORM";
    case 43:
      return "R8G8B8A8_SRGB";
    case 44:
      return "B8G8R8A8_UNORM";
    case 50:
      return "B8G8R8A8_SRGB";
    case 70:
      return "R16_UNORM";
    case 77:
      return "R16G16_UNORM";
    case 91:
      return "R16G16B16A16_UNORM";
    case 97:
      return "R16G16B16A16_SFLOAT";
    case 109:
      return "R32G32B32A32_SFLOAT";
    default:
      break;
  }
  // BC1 to BC7 (131-146) and ETC2/EAC (147-156), in Vulkan's order.
  static const char* kBlockNames[] = {
      "BC1_RGB_UNORM_BLOCK",       "BC1_RGB_SRGB_BLOCK",       "BC1_RGBA_UNORM_BLOCK",      "BC1_RGBA_SRGB_BLOCK",
      "BC2_UNORM_BLOCK",           "BC2_SRGB_BLOCK",           "BC3_UNORM_BLOCK",           "BC3_SRGB_BLOCK",
      "BC4_UNORM_BLOCK",           "BC4_SNORM_BLOCK",          "BC5_UNORM_BLOCK",           "BC5_SNORM_BLOCK",
      "BC6H_UFLOAT_BLOCK",         "BC6H_SFLOAT_BLOCK",        "BC7_UNORM_BLOCK",           "BC7_SRGB_BLOCK",
      "ETC2_R8G8B8_UNORM_BLOCK",   "ETC2_R8G8B8_SRGB_BLOCK",   "ETC2_R8G8B8A1_UNORM_BLOCK", "ETC2_R8G8B8A1_SRGB_BLOCK",
      "ETC2_R8G8B8A8_UNORM_BLOCK", "ETC2_R8G8B8A8_SRGB_BLOCK", "EAC_R11_UNORM_BLOCK",       "EAC_R11_SNORM_BLOCK",
      "EAC_R11G11_UNORM_BLOCK",    "EAC_R11G11_SNORM_BLOCK"};
  if (vk >= 131 && vk <= 156) return kBlockNames[vk - 131];
  // ASTC: 157 (4x4 UNORM) to 184 (12x12 SRGB), UNORM and SRGB alternating; SFLOAT from 1000066000.
  static const char* kFootprints[] = {"4x4", "5x4",  "5x5",  "6x5",  "6x6",   "8x5",   "8x6",
                                      "8x8", "10x5", "10x6", "10x8", "10x10", "12x10", "12x12"};
  if (vk >= 157 && vk <= 184) {
    return std::string("ASTC_") + kFootprints[(vk - 157) / 2] + ((vk - 157) % 2 ? "_SRGB_BLOCK" : "_UNORM_BLOCK");
  }
  if (vk >= 1000066000u && vk <= 1000066013u)
    return std::string("ASTC_") + kFootprints[vk - 1000066000u] + "_SFLOAT_BLOCK";
  if (vk >= 1000054000u && vk <= 1000054007u) return "PVRTC (IMG)";
  return "";
}

std::string dxgi_format_name(std::uint32_t dxgi) {
  switch (dxgi) {
    case 11:
      return "R16G16B16A16_UNORM";
    case 28:
      return "R8G8B8A8_UNORM";
    case 29:
      return "R8G8B8A8_UNORM_SRGB";
    case 35:
      return "R16G16_UNORM";
    case 49:
      return "R8G8_UNORM";
    case 56:
      return "R16_UNORM";
    case 61:
      return "R8_UNORM";
    case 71:
      return "BC1_UNORM";
    case 72:
      return "BC1_UNORM_SRGB";
    case 74:
      return "BC2_UNORM";
    case 75:
      return "BC2_UNORM_SRGB";
    case 77:
      return "BC3_UNORM";
    case 78:
      return "BC3_UNORM_SRGB";
    case 80:
      return "BC4_UNORM";
    case 81:
      return "BC4_SNORM";
    case 83:
      return "BC5_UNORM";
    case 84:
      return "BC5_SNORM";
    case 91:
      return "B8G8R8A8_UNORM_SRGB";
    case 94:
      return "BC6H_TYPELESS";
    case 95:
      return "BC6H_UF16";
    case 96:
      return "BC6H_SF16";
    case 97:
      return "BC7_TYPELESS";
    case 98:
      return "BC7_UNORM";
    case 99:
      return "BC7_UNORM_SRGB";
    case 2:
      return "R32G32B32A32_TYPELESS";
    case 10:
      return "R16G16B16A16_FLOAT";
    case 87:
      return "B8G8R8A8_UNORM";
    default:
      return "";
  }
}

}  // namespace texproc
