// Pixel memory (PixelBytes' blocks) and an allocator over it for the
// library's own scratch buffers.
#pragma once

#include <cstddef>
#include <new>
#include <utility>

namespace texproc::detail {

// Large blocks are 2 MiB aligned and marked for transparent huge pages, and
// freed ones are kept (up to 512 MiB) for the next block of their size.
void* allocate_pixels(std::size_t bytes);
void free_pixels(void* p, std::size_t bytes) noexcept;

// The whole pages inside [begin, begin + bytes) leave the process's resident
// memory: for a buffer whose bytes will not be read again, so that one
// being turned into another is not held twice. They read as zeros (private
// memory) or as the file again (a private file mapping) afterwards.
void discard_pages(const void* begin, std::size_t bytes) noexcept;

// An allocator over pixel memory whose resize() leaves new elements
// uninitialized: buffers that are about to be overwritten are not
// zero-filled first (at 4096x4096 the memset alone costs milliseconds).
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

}  // namespace texproc::detail
