// texproc/image.h: pixel types, a non-owning image view and an owning image.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <string>
#include <vector>

namespace texproc {

// The element type of one channel in memory. Half-float files are widened to
// f32 on read (and may be narrowed again on write, see image_io.h).
enum class PixelType : std::uint8_t { u8, u16, f32 };

// Bytes per channel of `t`.
constexpr std::size_t bytes_per_channel(PixelType t) {
  switch (t) {
    case PixelType::u8: return 1;
    case PixelType::u16: return 2;
    case PixelType::f32: return 4;
  }
  return 0;
}
constexpr bool is_float(PixelType t) { return t == PixelType::f32; }

// "u8", "u16", "f32".
const char* to_string(PixelType t);

// A read-only view of interleaved pixels in caller memory: what a call reads
// (its inputs). `row_stride` is in bytes and may exceed width * channels *
// bytes_per_channel(type) (padding, sub-views).
struct ConstImageView {
  const void* data = nullptr;
  int width = 0;
  int height = 0;
  int channels = 0;  // 1..4: gray, gray+alpha, RGB, RGBA
  PixelType type = PixelType::u8;
  std::size_t row_stride = 0;

  std::size_t pixel_bytes() const { return channels * bytes_per_channel(type); }
  template <typename T>
  const T* row(int y) const {
    assert(y >= 0 && y < height);
    return reinterpret_cast<const T*>(static_cast<const std::uint8_t*>(data) + y * row_stride);
  }
};

// A view of pixels a call writes (its outputs), laid out as ConstImageView;
// it converts to one, so an output may also be read. A const Image gives
// only a ConstImageView: it cannot be passed where a call writes.
struct ImageView {
  void* data = nullptr;
  int width = 0;
  int height = 0;
  int channels = 0;  // 1..4: gray, gray+alpha, RGB, RGBA
  PixelType type = PixelType::u8;
  std::size_t row_stride = 0;

  std::size_t pixel_bytes() const { return channels * bytes_per_channel(type); }
  template <typename T>
  T* row(int y) const {
    assert(y >= 0 && y < height);
    return reinterpret_cast<T*>(static_cast<std::uint8_t*>(data) + y * row_stride);
  }
  operator ConstImageView() const { return {data, width, height, channels, type, row_stride}; }
};

namespace detail {
// Pixel memory: large blocks are 2 MiB aligned and marked for transparent
// huge pages, so that filling a fresh 64 MiB level costs 32 page faults
// rather than 16384.
void* allocate_pixels(std::size_t bytes);
void free_pixels(void* p, std::size_t bytes) noexcept;
// Freed large blocks are kept (up to 512 MiB) for the next image of their
// size; this gives them back to the system (after freeing an image that
// nothing of its size will follow).
void release_cached_pixels() noexcept;

// An allocator whose resize() leaves new elements uninitialized: buffers that
// are about to be overwritten are not zero-filled first (at 4096x4096 the
// memset alone costs milliseconds).
template <typename T>
struct DefaultInitAllocator {
  using value_type = T;
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_pixels(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { free_pixels(p, n * sizeof(T)); }
  template <typename U>
  bool operator==(const DefaultInitAllocator<U>&) const noexcept {
    return true;
  }
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
}  // namespace detail

// Pixel or texel bytes in pixel memory (see allocate_pixels): what Image
// holds and what Texture's images are, so one can become the other without
// a copy.
// Converts to and from std::vector<std::uint8_t> (with a copy) for callers
// that hold bytes that way.
struct PixelBytes : std::vector<std::uint8_t, detail::DefaultInitAllocator<std::uint8_t>> {
  using Base = std::vector<std::uint8_t, detail::DefaultInitAllocator<std::uint8_t>>;
  using Base::Base;
  PixelBytes() = default;
  PixelBytes(Base&& b) noexcept : Base(std::move(b)) {}
  PixelBytes(const std::vector<std::uint8_t>& v) : Base(v.begin(), v.end()) {}
  operator std::vector<std::uint8_t>() const { return std::vector<std::uint8_t>(begin(), end()); }
  friend bool operator==(const PixelBytes& a, const PixelBytes& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator==(const PixelBytes& a, const std::vector<std::uint8_t>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
};

// An owning image with tightly packed rows.
class Image {
 public:
  Image() = default;
  // Allocates width*height*channels elements of `type`, zero-filled.
  // Asserts 1 <= channels <= 4 and positive sizes.
  Image(int width, int height, int channels, PixelType type);
  // The same, with the pixels left uninitialized, for callers that write
  // every pixel.
  static Image uninitialized(int width, int height, int channels, PixelType type);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  PixelType type() const { return type_; }
  bool empty() const { return data_.empty(); }
  std::size_t row_stride() const { return std::size_t(width_) * channels_ * bytes_per_channel(type_); }
  std::size_t byte_size() const { return data_.size(); }

  std::uint8_t* data() { return data_.data(); }
  const std::uint8_t* data() const { return data_.data(); }
  template <typename T>
  T* row(int y) { return reinterpret_cast<T*>(data_.data() + y * row_stride()); }
  template <typename T>
  const T* row(int y) const { return reinterpret_cast<const T*>(data_.data() + y * row_stride()); }

  ImageView view() { return {data_.data(), width_, height_, channels_, type_, row_stride()}; }
  ConstImageView view() const { return {data_.data(), width_, height_, channels_, type_, row_stride()}; }

  // Gives up the pixel bytes (rows tightly packed), leaving the image empty.
  PixelBytes release() && {
    width_ = height_ = channels_ = 0;
    return std::move(data_);
  }

  // Channel c of pixel (x, y) as a float: integers are scaled to [0, 1].
  float get(int x, int y, int c) const;
  // Sets channel c of pixel (x, y): integers are rounded and clamped.
  void set(int x, int y, int c, float v);

 private:
  int width_ = 0, height_ = 0, channels_ = 0;
  PixelType type_ = PixelType::u8;
  PixelBytes::Base data_;
};

// Sets every NaN and infinity of an f32 image to `value` and returns how
// many there were (0 for integer images). A filter would otherwise spread
// one bad texel over its whole footprint at every level.
std::size_t replace_non_finite(Image& image, float value = 0.0f);

}  // namespace texproc
