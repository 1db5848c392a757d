// texproc/transparent_color.h: what colour fully transparent texels keep.
#pragma once

#include <string_view>

#include "texproc/image.h"

namespace texproc {

enum class TransparentColor {
  keep,   // leave the stored colour (default)
  bleed,  // fill from the nearest visible texels, ring by ring (no dark fringes under filtering)
  zero    // black
};

TransparentColor parse_transparent_color(std::string_view name);  // throws Error{bad_arguments}

// Applies the policy to the texels of an RGBA8 image whose alpha is 0; other
// images are left alone. Alpha and visible texels never change.
void apply_transparent_color(Image& rgba8, TransparentColor policy);

}  // namespace texproc
