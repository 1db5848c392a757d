// A MIP-mapped tiled TIFF writer whose tiles are deflated on all threads.
#pragma once

#include <string>
#include <vector>

#include "texproc/image.h"

namespace texproc {

// True if write_tiff_levels handles this compression ("", "none", "zip",
// "zip:N", "deflate", "deflate:N", "lzw", "packbits").
bool tiff_levels_supported(const std::string& compression);

// Writes `levels` to `file` (the caller's temporary path) in 64x64 tiles with
// straight (unassociated) alpha. With mip_file, as maketx does: level 0 then
// reduced-resolution subimages, Pixar texture format "Plain Texture"; else
// the one image. `error_path` names the file in messages. Deflated tiles are
// compressed on all threads; LZW and PackBits through libtiff. Deflate level: N from "zip:N", else kDefaultZipLevel
// (level 1 with the horizontal predictor: files 8% larger than maketx's
// zip, written 4x faster; measured on the bench_mip image).
// Throws Error{io}.
inline constexpr int kDefaultZipLevel = 1;
void write_tiff_levels(const std::string& file, const std::string& error_path,
                       const std::vector<ConstImageView>& levels, bool mip_file, const std::string& compression);

}  // namespace texproc
