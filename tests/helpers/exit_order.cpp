// A program whose static frees pixel memory after every static the library
// made since has been destroyed, as oneTBB workers' thread_local scratch does
// when a busy process exits. It must exit 0: the block cache that pixel
// memory returns to outlives every destructor that can reach it.
#include <cstddef>
#include <vector>

#include "texproc/image.h"

namespace {
using Pixels = std::vector<float, texproc::detail::DefaultInitAllocator<float>>;
struct Holder {
  Pixels pixels;
};
}  // namespace

int main() {
  static Holder held;  // constructed before the library's cache: destroyed after it
  held.pixels.resize(std::size_t(4) << 20);  // 16 MiB: a large block
  {
    Pixels freed(std::size_t(4) << 20);  // freed into the cache, which now holds one block
    freed[0] = 1.0f;
  }
  held.pixels[0] = 2.0f;
  return held.pixels[0] == 2.0f ? 0 : 1;
}
