// BC1-BC7 images: the drivers that cut an image into blocks, gather them
// sixteen at a time for the lanes (or one at a time for `max`), and write the
// blocks, row by row over texproc's threads. compress_image dispatches here.
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/block_encode.h"

namespace texproc {

// BC1 (opaque and 1-bit alpha), BC2 and BC3: the colour block, and BC2's
// explicit or BC3's interpolated alpha.
std::vector<std::uint8_t> compress_bc13(const ConstImageView& img, TexelFormat format, Quality q,
                                        const EncodeOptions& options);
// BC7 (UNORM, sRGB: the same search on the stored values).
std::vector<std::uint8_t> compress_bc7(const ConstImageView& img, Quality q, const EncodeOptions& options);
// BC6H (UF16, SF16): RGB as half floats (8- and 16-bit input as [0, 1];
// gray fills RGB; alpha is dropped). UF16 stores negative values as 0.
std::vector<std::uint8_t> compress_bc6h(const ConstImageView& img, bool is_signed, Quality q,
                                        const EncodeOptions& options);
// BC4 and BC5 (UNORM, SNORM): one or two channels as data.
std::vector<std::uint8_t> compress_bc45(const ConstImageView& img, TexelFormat format, Quality q,
                                        const EncodeOptions& options);

}  // namespace texproc
