// JPEG through libjpeg-turbo's libjpeg API, with its defaults (islow IDCT,
// fancy upsampling), as OpenImageIO reads it: the same pixels. CMYK and
// YCCK files are left to the OpenImageIO module.
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <vector>

// jpeglib.h needs FILE and size_t first.
#include <jpeglib.h>
#include <jerror.h>

#include "core/fd_writer.h"
#include "io/codecs/codecs.h"
#include "texproc/error.h"

namespace texproc::codecs {
namespace {

struct ErrorManager {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
  bool over_limit = false;  // message says which limit, not a decoding error
};

// Stops a decoder whose file has more scans than the limit: libjpeg calls
// this between scans while it absorbs a progressive file.
struct ScanLimit {
  jpeg_progress_mgr pub;
  int max_scans;
};
void on_progress(j_common_ptr cinfo) {
  if (!cinfo->is_decompressor) return;
  const auto* d = reinterpret_cast<j_decompress_ptr>(cinfo);
  const auto* limit = reinterpret_cast<const ScanLimit*>(cinfo->progress);
  if (d->input_scan_number <= limit->max_scans) return;
  auto* e = reinterpret_cast<ErrorManager*>(cinfo->err);
  std::snprintf(e->message, sizeof e->message,
                "more than %d scans (a progressive file has about ten): refused, as each scan can cost a pass over "
                "the image; TEXPROC_MAX_JPEG_SCANS raises the limit",
                limit->max_scans);
  e->over_limit = true;
  std::longjmp(e->jump, 1);
}

void on_error(j_common_ptr cinfo) {
  auto* e = reinterpret_cast<ErrorManager*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, e->message);
  std::longjmp(e->jump, 1);
}

// libjpeg calls corrupt data (a truncated file, a bad Huffman code) a
// warning and goes on with grey blocks; texproc refuses such a file. Only
// extraneous bytes between markers, which many cameras write, pass.
void on_message(j_common_ptr cinfo, int level) {
  if (level < 0 && cinfo->err->msg_code != JWRN_EXTRANEOUS_DATA) cinfo->err->error_exit(cinfo);
}

// texproc's handlers on a codec's error manager (the setjmp stays in the
// caller's frame).
jpeg_error_mgr* install(ErrorManager& err) {
  jpeg_error_mgr* e = jpeg_std_error(&err.pub);
  err.pub.error_exit = on_error;
  err.pub.emit_message = on_message;
  return e;
}

struct Header {
  int width = 0, height = 0, channels = 0;
  J_COLOR_SPACE space = JCS_UNKNOWN;
};

// Everything between setjmp and the end of the decoder's life is plain C:
// no C++ object with a destructor lives in this frame.
bool decode(const FileBytes& f, Header& h, std::uint8_t* pixels, std::size_t row_stride, bool header_only,
            int max_scans, char* message, bool* over_limit = nullptr) {
  jpeg_decompress_struct cinfo;
  ErrorManager err;
  cinfo.err = install(err);
  ScanLimit limit{};
  limit.pub.progress_monitor = on_progress;
  limit.max_scans = max_scans;
  if (setjmp(err.jump)) {
    std::strcpy(message, err.message);
    if (over_limit) *over_limit = err.over_limit;
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  jpeg_create_decompress(&cinfo);
  cinfo.progress = &limit.pub;
  jpeg_mem_src(&cinfo, f.data(), (unsigned long)f.size());
  jpeg_read_header(&cinfo, TRUE);
  h.width = int(cinfo.image_width);
  h.height = int(cinfo.image_height);
  h.space = cinfo.jpeg_color_space;
  h.channels = cinfo.jpeg_color_space == JCS_GRAYSCALE ? 1 : cinfo.num_components == 4 ? 4 : 3;
  if (header_only || !pixels) {
    jpeg_destroy_decompress(&cinfo);
    return true;
  }
  cinfo.out_color_space = h.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&cinfo);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = pixels + std::size_t(cinfo.output_scanline) * row_stride;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return true;
}

ImageFileInfo info_of(const std::string& path, const Header& h, const ReadLimits& limits) {
  if (h.space == JCS_CMYK || h.space == JCS_YCCK || h.channels == 4) throw LeaveToModule{"CMYK JPEG"};
  ImageFileInfo info;
  info.format = "jpeg";
  info.width = h.width;
  info.height = h.height;
  info.channels = h.channels;
  info.file_type = "uint8";
  info.type = PixelType::u8;
  info.color_space_tag = "sRGB";
  info.level_sizes.emplace_back(h.width, h.height);
  check_size(path, h.width, h.height, h.channels, limits);
  return info;
}

}  // namespace

ImageFileInfo jpeg_probe(const std::string& path, const FileBytes& f, const ReadLimits& limits) {
  Header h;
  char message[JMSG_LENGTH_MAX] = {};
  if (!decode(f, h, nullptr, 0, true, limits.max_jpeg_scans, message))
    invalid(path, std::string("not a valid JPEG: ") + message);
  return info_of(path, h, limits);
}

Image jpeg_read(const std::string& path, const FileBytes& f, ImageFileInfo& info, const ReadLimits& limits) {
  info = jpeg_probe(path, f, limits);
  Image img = Image::uninitialized(info.width, info.height, info.channels, PixelType::u8);
  Header h;
  char message[JMSG_LENGTH_MAX] = {};
  bool over_limit = false;
  if (!decode(f, h, img.data(), img.row_stride(), false, limits.max_jpeg_scans, message, &over_limit)) {
    invalid(path, (over_limit ? std::string("JPEG with ") : std::string("cannot decode JPEG: ")) + message);
  }
  return img;
}

namespace {

bool encode(const std::uint8_t* rows, std::size_t stride, int width, int height, int channels, int quality,
            unsigned char** out, unsigned long* out_size, char* message) {
  jpeg_compress_struct cinfo;
  ErrorManager err;
  cinfo.err = install(err);
  if (setjmp(err.jump)) {
    std::strcpy(message, err.message);
    jpeg_destroy_compress(&cinfo);
    return false;
  }
  jpeg_create_compress(&cinfo);
  jpeg_mem_dest(&cinfo, out, out_size);
  cinfo.image_width = JDIMENSION(width);
  cinfo.image_height = JDIMENSION(height);
  cinfo.input_components = channels;
  cinfo.in_color_space = channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  static const char kComment[] = "texproc";
  jpeg_write_marker(&cinfo, JPEG_COM, reinterpret_cast<const JOCTET*>(kComment), sizeof kComment - 1);
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<std::uint8_t*>(rows + std::size_t(cinfo.next_scanline) * stride);
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  return true;
}

}  // namespace

void jpeg_write(const std::string& file, const std::string& path, const ConstImageView& v, const WriteOptions& o) {
  // JPEG holds gray or RGB in 8 bits: alpha is dropped, 16-bit and float
  // are rounded to 8 bits (clamped to [0, 1]), as OpenImageIO writes them.
  const int channels = v.channels >= 3 ? 3 : 1;
  std::vector<std::uint8_t> rows(std::size_t(v.width) * v.height * channels);
  for (int y = 0; y < v.height; ++y) {
    std::uint8_t* d = rows.data() + std::size_t(y) * v.width * channels;
    for (int x = 0; x < v.width; ++x) {
      for (int c = 0; c < channels; ++c)
        d[std::size_t(x) * channels + c] = sample_u8(v, y, std::size_t(x) * v.channels + c);
    }
  }
  unsigned char* out = nullptr;
  unsigned long size = 0;
  char message[JMSG_LENGTH_MAX] = {};
  const int quality = o.quality < 1 ? 1 : o.quality > 100 ? 100 : o.quality;
  const bool ok =
      encode(rows.data(), std::size_t(v.width) * channels, v.width, v.height, channels, quality, &out, &size, message);
  if (!ok) {
    std::free(out);
    write_error(path, std::string("JPEG encoder: ") + message);
  }
  try {
    FdWriter w(file, path);
    w.write(out, size);
    w.close();
  } catch (...) {
    std::free(out);
    throw;
  }
  std::free(out);
}

}  // namespace texproc::codecs
