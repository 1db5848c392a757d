// The image formats texproc reads and writes itself, each in its own file
// beside this header, behind one shape: probe (header facts only), read
// (pixels), write (one image into a temporary file). image_io.cpp picks the
// codec by the file's signature when reading and by the extension when
// writing; everything else goes to the OpenImageIO module.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "texproc/image.h"
#include "texproc/image_io.h"

namespace texproc::codecs {

// A whole input file in memory: a regular file is mapped (its pages read
// ahead when `read_ahead`, for a reader that decodes it all; a probe reads
// a header only), a pipe is read up to kMaxStreamBytes; devices, sockets and
// folders are refused (Error{io}).
//
// A mapped file truncated by another process while it is read would kill
// the process with SIGBUS: the pages past the new end read as zeros instead,
// and truncated() says so; readers then fail with check_intact().
class FileBytes {
 public:
  static constexpr std::size_t kMaxStreamBytes = std::size_t(1) << 30;
  explicit FileBytes(const std::string& path, bool read_ahead = true);  // throws Error{io}
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }
  // Tells the system that bytes [begin, begin + n) of a mapped file will
  // not be read again: the whole pages inside go out of the process's
  // resident memory (a reader that has turned them into pixels calls this,
  // so that a large input is not held twice). Nothing for a read file.
  void release(const std::uint8_t* begin, std::size_t n) const;
  // Whether the file shrank under the map while it was read.
  bool truncated() const;
  // Error{invalid_file} naming `path` if truncated().
  void check_intact(const std::string& path) const;

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  bool mapped_ = false;
  int slot_ = -1;  // in the table of guarded maps
  std::uint8_t* owned_ = nullptr;
};

// Thrown by a direct reader for a valid file in a layout it leaves to
// OpenImageIO (a CMYK JPEG, a palette TIFF, ...): image_io.cpp then asks the
// module, as for a format with no direct reader.
struct LeaveToModule {
  std::string why;
};

// Refuses (Error{invalid_file}) a declared size past `limits` before
// anything is allocated for it.
void check_size(const std::string& path, long long width, long long height, int channels, const ReadLimits& limits);

// Sample i of row y as 8 bits, for the formats that hold only 8 (JPEG, TGA):
// 16-bit rounded, float clamped to [0, 1] (NaN as 0) and rounded.
std::uint8_t sample_u8(const ConstImageView& v, int y, std::size_t i);

// [[noreturn]] helpers for the readers' messages: "PATH: what".
[[noreturn]] void invalid(const std::string& path, const std::string& what);
[[noreturn]] void write_error(const std::string& path, const std::string& what);

// PNG (libspng reads; texproc's writer filters and deflates strips of rows
// in parallel with zlib).
ImageFileInfo png_probe(const std::string& path, const FileBytes& f, const ReadLimits& limits);
Image png_read(const std::string& path, const FileBytes& f, ImageFileInfo& info, const ReadLimits& limits);
void png_write(const std::string& file, const std::string& path, const ConstImageView& v, const WriteOptions& o);
// The same for rows made on demand: `shape` gives the size, channels and
// type (no pixels); each strip asks `source` for its rows.
void png_write(const std::string& file, const std::string& path, const ConstImageView& shape, const RowSource& source,
               const WriteOptions& o);

// JPEG (libjpeg-turbo).
ImageFileInfo jpeg_probe(const std::string& path, const FileBytes& f, const ReadLimits& limits);
Image jpeg_read(const std::string& path, const FileBytes& f, ImageFileInfo& info, const ReadLimits& limits);
void jpeg_write(const std::string& file, const std::string& path, const ConstImageView& v, const WriteOptions& o);

// Truevision TGA (texproc's own: the format is a header and rows).
ImageFileInfo tga_probe(const std::string& path, const FileBytes& f, const ReadLimits& limits);
Image tga_read(const std::string& path, const FileBytes& f, ImageFileInfo& info, const ReadLimits& limits);
void tga_write(const std::string& file, const std::string& path, const ConstImageView& v, const WriteOptions& o);

// OpenEXR: the texproc_exr module (io/modules/), loaded on first use.

// TIFF (libtiff; deflate strips and tiles inflated in parallel).
ImageFileInfo tiff_probe(const std::string& path, const ReadLimits& limits);
Image tiff_read(const std::string& path, ImageFileInfo& info, const ReadLimits& limits);

// libtiff's messages go to the thread's last-error string instead of stderr.
void quiet_libtiff();
std::string libtiff_last_error();

// GPU containers as images: level 0, layer 0, face 0 (decoded if compressed).
ImageFileInfo container_probe(const std::string& path, const ReadLimits& limits);
Image container_read(const std::string& path, ImageFileInfo& info, const ReadLimits& limits);
ImageArray container_read_all(const std::string& path, ImageFileInfo& info, const ReadLimits& limits);
ImageChains container_read_chains(const std::string& path, ImageFileInfo& info, const ReadLimits& limits,
                                  std::uint32_t max_levels);

}  // namespace texproc::codecs
