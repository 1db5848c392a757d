// A MIP-mapped tiled TIFF writer whose tiles are deflated on all threads.
#pragma once

#include <string>
#include <vector>

#include "texproc/image.h"

namespace texproc {

// True if write_tiff_mips handles this compression ("", "none", "zip",
// "zip:N", "deflate", "deflate:N") for levels of `type`.
bool tiff_mips_supported(const std::string& compression);

// Writes `levels` to `file` (the caller's temporary path) as maketx does:
// 64x64 tiles, level 0 then reduced-resolution subimages, Pixar texture
// format "Plain Texture", straight (unassociated) alpha. `error_path` names
// the file in messages. Deflate level: N from "zip:N", else kDefaultZipLevel
// (level 1 with the horizontal predictor: files 8% larger than maketx's
// zip, written 4x faster; measured on the bench_mip image).
// Throws Error{io}.
inline constexpr int kDefaultZipLevel = 1;
void write_tiff_mips(const std::string& file, const std::string& error_path, const std::vector<Image>& levels,
                     const std::string& compression, const std::string& color_space);

}  // namespace texproc
