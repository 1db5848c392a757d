// What the direct image codecs share: the input file in memory, size limits,
// messages.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "image/codecs/codecs.h"
#include "texproc/error.h"

namespace texproc::codecs {

FileBytes::FileBytes(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorCode::io, path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    throw Error(ErrorCode::io, path + ": cannot open: " + std::strerror(err));
  }
  size_ = std::size_t(st.st_size);
  if (size_ > 0 && S_ISREG(st.st_mode)) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (p != MAP_FAILED) {
      data_ = static_cast<const std::uint8_t*>(p);
      mapped_ = true;
      ::close(fd);
      return;
    }
  }
  // Pipes, special files, or a failed map: read it all.
  std::size_t cap = size_ ? size_ : 1 << 16, n = 0;
  owned_ = static_cast<std::uint8_t*>(std::malloc(cap));
  for (;;) {
    if (n == cap) owned_ = static_cast<std::uint8_t*>(std::realloc(owned_, cap *= 2));
    const ssize_t r = ::read(fd, owned_ + n, cap - n);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      const int err = errno;
      ::close(fd);
      std::free(owned_);
      owned_ = nullptr;
      throw Error(ErrorCode::io, path + ": cannot read: " + std::strerror(err));
    }
    if (r == 0) break;
    n += std::size_t(r);
  }
  ::close(fd);
  data_ = owned_;
  size_ = n;
}

FileBytes::~FileBytes() {
  if (mapped_) ::munmap(const_cast<std::uint8_t*>(data_), size_);
  std::free(owned_);
}

std::uint8_t sample_u8(const ImageView& v, int y, std::size_t i) {
  if (v.type == PixelType::u8) return v.row<const std::uint8_t>(y)[i];
  if (v.type == PixelType::u16) return std::uint8_t((unsigned(v.row<const std::uint16_t>(y)[i]) * 255u + 32767u) / 65535u);
  float f = v.row<const float>(y)[i];
  f = f != f ? 0.0f : f < 0.0f ? 0.0f : f > 1.0f ? 1.0f : f;
  return std::uint8_t(f * 255.0f + 0.5f);
}

void check_size(const std::string& path, long long width, long long height, int channels) {
  if (width <= 0 || height <= 0 || channels <= 0) invalid(path, "image has no pixels");
  const ImageReadLimits l = image_read_limits();
  if (width > l.max_dimension || height > l.max_dimension || width * height > l.max_pixels) {
    throw Error(ErrorCode::invalid_file,
                path + ": declared size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is past the limit of " + std::to_string(l.max_pixels) + " pixels, " +
                    std::to_string(l.max_dimension) + " a side (TEXPROC_MAX_IMAGE_PIXELS raises it)");
  }
}

void invalid(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::invalid_file, path + ": " + what);
}

void write_error(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::io, path + ": cannot write: " + what);
}

}  // namespace texproc::codecs
