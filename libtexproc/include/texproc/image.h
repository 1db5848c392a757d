// texproc/image.h: pixel types, read-only and writable image views, pixel
// memory and an owning image.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <string>
#include <type_traits>
#include <vector>

namespace texproc {

// The element type of one channel in memory. Half-float files are widened to
// f32 on read (and may be narrowed again on write, see image_io.h).
enum class PixelType : std::uint8_t { u8, u16, f32 };

// Bytes per channel of `t`.
constexpr std::size_t bytes_per_channel(PixelType t) {
  switch (t) {
    case PixelType::u8:
      return 1;
    case PixelType::u16:
      return 2;
    case PixelType::f32:
      return 4;
  }
  return 0;
}
constexpr bool is_float(PixelType t) { return t == PixelType::f32; }

// "u8", "u16", "f32".
const char* to_string(PixelType t);

// A view of interleaved pixels in caller memory. `row_stride` is in bytes
// and may exceed width * channels * bytes_per_channel(type) (padding,
// sub-views). Two kinds, told apart by type:
//   ConstImageView (Void = const void): read-only, what a call reads (its inputs);
//   ImageView (Void = void): what a call writes (its outputs). It converts
//   to a ConstImageView, so an output may also be read; a const Image gives
//   only a ConstImageView, which cannot be passed where a call writes.
template <typename Void>
struct BasicImageView {
  using Byte = std::conditional_t<std::is_const_v<Void>, const std::uint8_t, std::uint8_t>;
  template <typename T>
  using Ptr = std::conditional_t<std::is_const_v<Void>, const T*, T*>;

  Void* data = nullptr;
  int width = 0;
  int height = 0;
  int channels = 0;  // 1..4: gray, gray+alpha, RGB, RGBA
  PixelType type = PixelType::u8;
  std::size_t row_stride = 0;

  std::size_t pixel_bytes() const { return channels * bytes_per_channel(type); }
  template <typename T>
  Ptr<T> row(int y) const {
    assert(y >= 0 && y < height);
    return reinterpret_cast<Ptr<T>>(static_cast<Byte*>(data) + y * row_stride);
  }
  operator BasicImageView<const void>() const requires(!std::is_const_v<Void>) {
    return {data, width, height, channels, type, row_stride};
  }
};
using ConstImageView = BasicImageView<const void>;
using ImageView = BasicImageView<void>;

// Pixel or texel bytes: what Image holds and what Texture's images are, so
// one becomes the other without a copy. Large blocks come from texproc's
// pixel memory: 2 MiB aligned and marked for transparent huge pages (filling
// a fresh 64 MiB level costs 32 page faults rather than 16384), and kept
// for the next block of their size when freed (see
// release_cached_pixel_memory). New bytes are left uninitialized unless a
// value is given: buffers about to be overwritten are not zero-filled first.
class PixelBytes {
 public:
  PixelBytes() = default;
  explicit PixelBytes(std::size_t size);  // uninitialized
  PixelBytes(std::size_t size, std::uint8_t value);
  PixelBytes(const std::uint8_t* first, const std::uint8_t* last);
  PixelBytes(const std::vector<std::uint8_t>& bytes);  // a copy
  PixelBytes(const PixelBytes& other);
  PixelBytes(PixelBytes&& other) noexcept;
  PixelBytes& operator=(const PixelBytes& other);
  PixelBytes& operator=(PixelBytes&& other) noexcept;
  ~PixelBytes();

  std::uint8_t* data() { return data_; }
  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::uint8_t* begin() { return data_; }
  std::uint8_t* end() { return data_ + size_; }
  const std::uint8_t* begin() const { return data_; }
  const std::uint8_t* end() const { return data_ + size_; }
  std::uint8_t& operator[](std::size_t i) {
    assert(i < size_);
    return data_[i];
  }
  const std::uint8_t& operator[](std::size_t i) const {
    assert(i < size_);
    return data_[i];
  }
  // Keeps the first min(size, size()) bytes; bytes past them are uninitialized.
  void resize(std::size_t size);
  // Holds a copy of [first, last) instead.
  void assign(const std::uint8_t* first, const std::uint8_t* last) { *this = PixelBytes(first, last); }
  void clear() noexcept;

  // A copy, for callers that hold bytes in a std::vector.
  operator std::vector<std::uint8_t>() const { return std::vector<std::uint8_t>(begin(), end()); }
  friend bool operator==(const PixelBytes& a, const PixelBytes& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator==(const PixelBytes& a, const std::vector<std::uint8_t>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }

 private:
  std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

// Gives the freed large blocks that pixel memory keeps for reuse (up to
// 512 MiB) back to the system: after freeing an image that nothing of its
// size will follow.
void release_cached_pixel_memory() noexcept;

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
  T* row(int y) {
    return reinterpret_cast<T*>(data_.data() + y * row_stride());
  }
  template <typename T>
  const T* row(int y) const {
    return reinterpret_cast<const T*>(data_.data() + y * row_stride());
  }

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
  PixelBytes data_;
};

// Sets every NaN and infinity of an f32 image to `value` and returns how
// many there were (0 for integer images). A filter would otherwise spread
// one bad texel over its whole footprint at every level.
std::size_t replace_non_finite(Image& image, float value = 0.0f);

// Rows [y0, y1) of an image, made on demand (decoded, converted) into `dst`,
// rows `row_stride` bytes apart: called from several threads at once, for
// any range, and a row may be asked for more than once.
using RowSource = std::function<void(int y0, int y1, void* dst, std::size_t row_stride)>;

}  // namespace texproc
