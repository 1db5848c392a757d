// Names of GPU formats texproc does not read, for messages that say what a
// file holds ("vkFormat 145 (BC7_UNORM_BLOCK)") instead of a number alone.
#pragma once

#include <cstdint>
#include <string>

namespace texproc {

std::string vk_format_name(std::uint32_t vk);      // "" if unknown
std::string dxgi_format_name(std::uint32_t dxgi);  // "" if unknown

}  // namespace texproc
