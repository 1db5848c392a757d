// A program whose static frees pixel memory after every static the library
// made since has been destroyed, as oneTBB workers' thread_local scratch does
// when a busy process exits. It must exit 0: the block cache that pixel
// memory returns to outlives every destructor that can reach it.
#include <cstddef>

#include "texproc/image.h"

int main() {
  static texproc::PixelBytes held;     // constructed before the library's cache: destroyed after it
  held.resize(std::size_t(16) << 20);  // 16 MiB: a large block
  {
    texproc::PixelBytes freed(std::size_t(16) << 20);  // freed into the cache, which now holds one block
    freed[0] = 1;
  }
  held[0] = 2;
  return held[0] == 2 ? 0 : 1;
}
