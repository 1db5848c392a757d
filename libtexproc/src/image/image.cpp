#include "texproc/image.h"

#include <cmath>
#include <cstring>
#include <cstdlib>
#include <new>

#include <sys/mman.h>

namespace texproc {

namespace detail {
namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kLargeBlock = std::size_t(4) << 20;
}  // namespace

void* allocate_pixels(std::size_t bytes) {
  if (bytes < kLargeBlock) {
    void* p = ::operator new(bytes);
    return p;
  }
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
  ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: harmless where THP is off
  return p;
}

void free_pixels(void* p, std::size_t bytes) noexcept {
  if (bytes < kLargeBlock) {
    ::operator delete(p);
  } else {
    std::free(p);
  }
}
}  // namespace detail

const char* to_string(PixelType t) {
  switch (t) {
    case PixelType::u8: return "u8";
    case PixelType::u16: return "u16";
    case PixelType::f32: return "f32";
  }
  return "?";
}

Image::Image(int width, int height, int channels, PixelType type)
    : width_(width), height_(height), channels_(channels), type_(type) {
  assert(width > 0 && height > 0 && channels >= 1 && channels <= 4);
  data_.assign(std::size_t(width) * height * channels * bytes_per_channel(type), 0);
}

Image Image::uninitialized(int width, int height, int channels, PixelType type) {
  assert(width > 0 && height > 0 && channels >= 1 && channels <= 4);
  Image img;
  img.width_ = width;
  img.height_ = height;
  img.channels_ = channels;
  img.type_ = type;
  img.data_.resize(std::size_t(width) * height * channels * bytes_per_channel(type));
  return img;
}

float Image::get(int x, int y, int c) const {
  assert(x >= 0 && x < width_ && y >= 0 && y < height_ && c >= 0 && c < channels_);
  const std::size_t i = std::size_t(x) * channels_ + c;
  switch (type_) {
    case PixelType::u8: return row<std::uint8_t>(y)[i] / 255.0f;
    case PixelType::u16: return row<std::uint16_t>(y)[i] / 65535.0f;
    case PixelType::f32: return row<float>(y)[i];
  }
  return 0.0f;
}

void Image::set(int x, int y, int c, float v) {
  assert(x >= 0 && x < width_ && y >= 0 && y < height_ && c >= 0 && c < channels_);
  const std::size_t i = std::size_t(x) * channels_ + c;
  const float cl = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  switch (type_) {
    case PixelType::u8: row<std::uint8_t>(y)[i] = static_cast<std::uint8_t>(cl * 255.0f + 0.5f); break;
    case PixelType::u16: row<std::uint16_t>(y)[i] = static_cast<std::uint16_t>(cl * 65535.0f + 0.5f); break;
    case PixelType::f32: row<float>(y)[i] = v; break;
  }
}

}  // namespace texproc
