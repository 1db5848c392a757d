#include "texproc/image.h"

#include "core/pixel_memory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdlib>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

namespace texproc {

namespace detail {
namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kLargeBlock = std::size_t(4) << 20;
}  // namespace

// Freed large blocks are kept (up to kCacheBytes) and handed out again to a
// request of the same rounded size: a batch of same-sized textures, or the
// levels of successive chains, then reuse memory whose pages are already
// mapped instead of faulting in (and zeroing) fresh ones.
constexpr std::size_t kCacheBytes = std::size_t(512) << 20;

struct BlockCache {
  std::mutex mutex;
  std::vector<std::pair<void*, std::size_t>> blocks;
  std::size_t bytes = 0;
};
// Never destroyed: pixel memory is freed by destructors that may run after
// this file's statics are gone (oneTBB workers' thread_local scratch runs its
// destructors after exit() has begun destroying statics, a static Image of a
// program's own). The cached blocks go back to the system with the process.
BlockCache& cache() {
  static BlockCache* c = new BlockCache;
  return *c;
}

std::size_t rounded_size(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

void* allocate_pixels(std::size_t bytes) {
  if (bytes < kLargeBlock) return ::operator new(bytes);
  const std::size_t rounded = rounded_size(bytes);
  {
    BlockCache& c = cache();
    std::lock_guard<std::mutex> lock(c.mutex);
    for (std::size_t i = 0; i < c.blocks.size(); ++i) {
      if (c.blocks[i].second == rounded) {
        void* p = c.blocks[i].first;
        c.blocks.erase(c.blocks.begin() + std::ptrdiff_t(i));
        c.bytes -= rounded;
        return p;
      }
    }
  }
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
  ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: harmless where THP is off
  return p;
}

void free_pixels(void* p, std::size_t bytes) noexcept {
  if (bytes < kLargeBlock) {
    ::operator delete(p);
    return;
  }
  const std::size_t rounded = rounded_size(bytes);
  BlockCache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  if (c.bytes + rounded <= kCacheBytes) {
    try {
      c.blocks.emplace_back(p, rounded);
      c.bytes += rounded;
      return;
    } catch (...) {
    }
  }
  std::free(p);
}

void discard_pages(const void* begin, std::size_t bytes) noexcept {
  static const auto page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  const auto at = reinterpret_cast<std::uintptr_t>(begin);
  const std::uintptr_t first = (at + page - 1) & ~(page - 1);
  const std::uintptr_t last = (at + bytes) & ~(page - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
}

}  // namespace detail

void release_cached_pixel_memory() noexcept {
  detail::BlockCache& c = detail::cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  for (const auto& b : c.blocks) std::free(b.first);
  c.blocks.clear();
  c.bytes = 0;
}

PixelBytes::PixelBytes(std::size_t size) : size_(size) {
  if (size) data_ = static_cast<std::uint8_t*>(detail::allocate_pixels(size));
}

PixelBytes::PixelBytes(std::size_t size, std::uint8_t value) : PixelBytes(size) {
  if (size) std::memset(data_, value, size);
}

PixelBytes::PixelBytes(const std::uint8_t* first, const std::uint8_t* last) : PixelBytes(std::size_t(last - first)) {
  if (size_) std::memcpy(data_, first, size_);
}

PixelBytes::PixelBytes(const std::vector<std::uint8_t>& bytes)
    : PixelBytes(bytes.data(), bytes.data() + bytes.size()) {}

PixelBytes::PixelBytes(const PixelBytes& other) : PixelBytes(other.begin(), other.end()) {}

PixelBytes::PixelBytes(PixelBytes&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

PixelBytes& PixelBytes::operator=(const PixelBytes& other) {
  if (this != &other) *this = PixelBytes(other);
  return *this;
}

PixelBytes& PixelBytes::operator=(PixelBytes&& other) noexcept {
  if (this != &other) {
    clear();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

PixelBytes::~PixelBytes() { clear(); }

void PixelBytes::resize(std::size_t size) {
  if (size == size_) return;
  PixelBytes bigger(size);
  if (size && size_) std::memcpy(bigger.data_, data_, std::min(size, size_));
  *this = std::move(bigger);
}

void PixelBytes::clear() noexcept {
  if (data_) detail::free_pixels(data_, size_);
  data_ = nullptr;
  size_ = 0;
}

const char* to_string(PixelType t) {
  switch (t) {
    case PixelType::u8:
      return "u8";
    case PixelType::u16:
      return "u16";
    case PixelType::f32:
      return "f32";
  }
  return "?";
}

Image::Image(int width, int height, int channels, PixelType type)
    : width_(width), height_(height), channels_(channels), type_(type) {
  assert(width > 0 && height > 0 && channels >= 1 && channels <= 4);
  data_ = PixelBytes(std::size_t(width) * height * channels * bytes_per_channel(type), 0);
}

Image Image::uninitialized(int width, int height, int channels, PixelType type) {
  assert(width > 0 && height > 0 && channels >= 1 && channels <= 4);
  Image img;
  img.width_ = width;
  img.height_ = height;
  img.channels_ = channels;
  img.type_ = type;
  img.data_ = PixelBytes(std::size_t(width) * height * channels * bytes_per_channel(type));
  return img;
}

float Image::get(int x, int y, int c) const {
  assert(x >= 0 && x < width_ && y >= 0 && y < height_ && c >= 0 && c < channels_);
  const std::size_t i = std::size_t(x) * channels_ + c;
  switch (type_) {
    case PixelType::u8:
      return row<std::uint8_t>(y)[i] / 255.0f;
    case PixelType::u16:
      return row<std::uint16_t>(y)[i] / 65535.0f;
    case PixelType::f32:
      return row<float>(y)[i];
  }
  return 0.0f;
}

void Image::set(int x, int y, int c, float v) {
  assert(x >= 0 && x < width_ && y >= 0 && y < height_ && c >= 0 && c < channels_);
  const std::size_t i = std::size_t(x) * channels_ + c;
  const float cl = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  switch (type_) {
    case PixelType::u8:
      row<std::uint8_t>(y)[i] = static_cast<std::uint8_t>(cl * 255.0f + 0.5f);
      break;
    case PixelType::u16:
      row<std::uint16_t>(y)[i] = static_cast<std::uint16_t>(cl * 65535.0f + 0.5f);
      break;
    case PixelType::f32:
      row<float>(y)[i] = v;
      break;
  }
}

std::size_t replace_non_finite(Image& image, float value) {
  if (image.type() != PixelType::f32) return 0;
  std::size_t n = 0;
  float* p = reinterpret_cast<float*>(image.data());
  const std::size_t count = image.byte_size() / sizeof(float);
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(p[i])) {
      p[i] = value;
      ++n;
    }
  }
  return n;
}

}  // namespace texproc
