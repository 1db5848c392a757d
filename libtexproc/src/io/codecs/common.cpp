// What the direct image codecs share: the input file in memory, size limits,
// messages.
#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "core/pixel_memory.h"
#include "io/codecs/codecs.h"
#include "texproc/error.h"

namespace texproc::codecs {

namespace {

// Maps whose pages past a truncation must read as zeros: the SIGBUS handler
// looks the faulting address up here (lock-free: it runs inside the fault).
struct GuardedMap {
  std::atomic<std::uintptr_t> begin{0};
  std::atomic<std::size_t> size{0};
  std::atomic<bool> truncated{false};
};
constexpr int kGuardedMaps = 256;
GuardedMap g_maps[kGuardedMaps];
struct sigaction g_previous_bus {};

void on_bus(int sig, siginfo_t* info, void* context) {
  const auto addr = reinterpret_cast<std::uintptr_t>(info->si_addr);
  for (GuardedMap& m : g_maps) {
    const std::uintptr_t b = m.begin.load(std::memory_order_acquire);
    if (b == 0 || addr < b || addr - b >= m.size.load(std::memory_order_acquire)) continue;
    // A page of zeros over the page that is gone; the read is retried.
    const std::uintptr_t page = addr & ~std::uintptr_t(::sysconf(_SC_PAGESIZE) - 1);
    if (::mmap(reinterpret_cast<void*>(page), std::size_t(::sysconf(_SC_PAGESIZE)), PROT_READ,
               MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) == MAP_FAILED) {
      break;
    }
    m.truncated.store(true, std::memory_order_release);
    return;
  }
  // Not one of ours: what would have happened without this handler.
  if (g_previous_bus.sa_flags & SA_SIGINFO) {
    if (g_previous_bus.sa_sigaction) return g_previous_bus.sa_sigaction(sig, info, context);
  } else if (g_previous_bus.sa_handler != SIG_DFL && g_previous_bus.sa_handler != SIG_IGN) {
    return g_previous_bus.sa_handler(sig);
  }
  ::signal(SIGBUS, SIG_DFL);  // returning re-runs the access, which now kills as it would have
}

void install_bus_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction sa {};
    sa.sa_sigaction = on_bus;
    sa.sa_flags = SA_SIGINFO | SA_NODEFER;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGBUS, &sa, &g_previous_bus);
  });
}

int guard(const void* p, std::size_t size) {
  install_bus_handler();
  for (int i = 0; i < kGuardedMaps; ++i) {
    std::uintptr_t expected = 0;
    if (g_maps[i].begin.compare_exchange_strong(expected, std::uintptr_t(1))) {  // claimed
      g_maps[i].truncated.store(false);
      g_maps[i].size.store(size, std::memory_order_release);
      g_maps[i].begin.store(reinterpret_cast<std::uintptr_t>(p), std::memory_order_release);
      return i;
    }
  }
  return -1;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

FileBytes::FileBytes(const std::string& path, bool read_ahead) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorCode::io, path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    throw Error(ErrorCode::io, path + ": cannot open: " + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) {
    ::close(fd);
    throw Error(ErrorCode::invalid_file,
                path + ": cannot read " + kind_of(st.st_mode) + " as an image (a file or a pipe is read)");
  }
  size_ = std::size_t(st.st_size);
  if (size_ > 0 && S_ISREG(st.st_mode)) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | (read_ahead ? MAP_POPULATE : 0), fd, 0);
    if (p != MAP_FAILED) {
      slot_ = guard(p, size_);
      if (slot_ >= 0) {
        data_ = static_cast<const std::uint8_t*>(p);
        mapped_ = true;
        ::close(fd);
        return;
      }
      ::munmap(p, size_);  // every guard taken: read it instead
    }
  }
  // Pipes, or a map that failed: read it all, up to the limit.
  std::size_t cap = size_ ? size_ : 1 << 16, n = 0;
  owned_ = static_cast<std::uint8_t*>(std::malloc(cap));
  auto fail = [&](const std::string& what) {
    ::close(fd);
    std::free(owned_);
    owned_ = nullptr;
    throw Error(ErrorCode::io, path + ": " + what);
  };
  if (!owned_) fail("cannot read: out of memory");
  for (;;) {
    if (n == cap) {
      if (cap >= kMaxStreamBytes)
        fail("more than " + std::to_string(kMaxStreamBytes >> 20) + " MiB from a pipe: refused");
      auto* grown = static_cast<std::uint8_t*>(std::realloc(owned_, std::min(cap * 2, kMaxStreamBytes)));
      if (!grown) fail("cannot read: out of memory");
      owned_ = grown;
      cap = std::min(cap * 2, kMaxStreamBytes);
    }
    const ssize_t r = ::read(fd, owned_ + n, cap - n);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) fail(std::string("cannot read: ") + std::strerror(errno));
    if (r == 0) break;
    n += std::size_t(r);
  }
  ::close(fd);
  data_ = owned_;
  size_ = n;
}

FileBytes::~FileBytes() {
  if (mapped_) {
    ::munmap(const_cast<std::uint8_t*>(data_), size_);
    g_maps[slot_].size.store(0, std::memory_order_release);
    g_maps[slot_].begin.store(0, std::memory_order_release);
  }
  std::free(owned_);
}

void FileBytes::release(const std::uint8_t* begin, std::size_t n) const {
  if (!mapped_ || begin < data_ || begin + n > data_ + size_) return;
  detail::discard_pages(begin, n);
}

bool FileBytes::truncated() const { return mapped_ && g_maps[slot_].truncated.load(std::memory_order_acquire); }

void FileBytes::check_intact(const std::string& path) const {
  if (truncated()) invalid(path, "the file was truncated while it was read (rewritten by another program?)");
}

std::uint8_t sample_u8(const ConstImageView& v, int y, std::size_t i) {
  if (v.type == PixelType::u8) return v.row<const std::uint8_t>(y)[i];
  if (v.type == PixelType::u16)
    return std::uint8_t((unsigned(v.row<const std::uint16_t>(y)[i]) * 255u + 32767u) / 65535u);
  float f = v.row<const float>(y)[i];
  f = f != f ? 0.0f : f < 0.0f ? 0.0f : f > 1.0f ? 1.0f : f;
  return std::uint8_t(f * 255.0f + 0.5f);
}

void check_size(const std::string& path, long long width, long long height, int channels, const ReadLimits& l) {
  if (width <= 0 || height <= 0 || channels <= 0) invalid(path, "image has no pixels");
  if (width > l.max_image_dimension || height > l.max_image_dimension || width * height > l.max_image_pixels) {
    throw Error(ErrorCode::invalid_file,
                path + ": declared size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is past the limit of " + std::to_string(l.max_image_pixels) + " pixels, " +
                    std::to_string(l.max_image_dimension) + " a side (TEXPROC_MAX_IMAGE_PIXELS raises it)");
  }
}

void invalid(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::invalid_file, path + ": " + what);
}

void write_error(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::io, path + ": cannot write: " + what);
}

}  // namespace texproc::codecs
