// The encode dispatcher: compress_image and encode_block send each format to
// its codec (BC1-BC7: bc/bc_images.cpp; ETC1, ETC2, EAC:
// etc/etc_encode.cpp; ASTC: astc/, through astc-encoder), and the quality
// names.
#include <cstring>
#include <string>

#include "astc/astc_encode.h"
#include "bc/bc_images.h"
#include "etc/etc_encode.h"
#include "texproc/block_encode.h"
#include "texproc/error.h"

namespace texproc {

Quality parse_quality(std::string_view n) {
  if (n == "fast") return Quality::fast;
  if (n == "normal") return Quality::normal;
  if (n == "high") return Quality::high;
  if (n == "max") return Quality::max;
  throw Error(ErrorCode::bad_arguments,
              "unknown quality name '" + std::string(n) + "' (valid: fast, normal, high, max)");
}

const char* to_string(Quality q) {
  switch (q) {
    case Quality::fast:
      return "fast";
    case Quality::normal:
      return "normal";
    case Quality::high:
      return "high";
    case Quality::max:
      return "max";
  }
  return "?";
}

std::vector<std::uint8_t> compress_image(const ConstImageView& img, TexelFormat format, Quality q) {
  return compress_image(img, format, q, EncodeOptions{});
}

int encode_block(TexelFormat format, const std::uint8_t rgba[16][4], Quality q, std::uint8_t* out,
                 const EncodeOptions& options) {
  std::uint8_t texels[16][4];
  std::memcpy(texels, rgba, sizeof texels);
  ImageView view;
  view.data = texels;
  view.width = view.height = 4;
  view.channels = 4;
  view.type = PixelType::u8;
  view.row_stride = 16;
  const std::vector<std::uint8_t> block = compress_image(view, format, q, options);
  std::memcpy(out, block.data(), block.size());
  return int(block.size());
}

std::vector<std::uint8_t> compress_image(const ConstImageView& img, TexelFormat format, Quality q,
                                         const EncodeOptions& options) {
  switch (format_info(format).family) {
    case CodecFamily::bc1:
    case CodecFamily::bc2:
    case CodecFamily::bc3:
      return compress_bc13(img, format, q, options);
    case CodecFamily::bc4:
    case CodecFamily::bc5:
      return compress_bc45(img, format, q, options);
    case CodecFamily::bc6h:
      return compress_bc6h(img, format == TexelFormat::bc6h_sfloat, q, options);
    case CodecFamily::bc7:
      return compress_bc7(img, q, options);
    case CodecFamily::etc1:
    case CodecFamily::etc2:
    case CodecFamily::eac:
      return etc::compress_etc(img, format, q, options);
    case CodecFamily::astc:
      return astc::encode(img, format, q, options);
    case CodecFamily::uncompressed:
      break;
  }
  throw Error(ErrorCode::unsupported, std::string("encoding ") + format_info(format).name + " is not supported");
}

}  // namespace texproc
