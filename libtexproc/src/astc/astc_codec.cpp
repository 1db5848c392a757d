// ASTC through libastcenc (astc-encoder 4.x, as Debian packages it). The
// library is opened with dlopen on first use: the texproc binary does not
// link it, so every run that never touches ASTC starts as before.
//
// Threads: one context per (profile, footprint, effort, flags, thread count),
// kept in a pool and reused for every level and file of the run; texproc's
// worker threads enter astcenc_compress_image with their own thread index
// and the library hands out blocks. Each block is searched on its own, so
// the bytes do not depend on which thread took it, nor on the thread count.
#define ASTCENC_DYNAMIC_LIBRARY 1
#include "astc/astc_decode.h"
#include "astc/astc_encode.h"

#include <astcenc.h>
#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <string>
#include <type_traits>

#include "texproc/error.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_ASTCENC_SONAME
#define TEXPROC_ASTCENC_SONAME "libastcenc.so"
#endif

namespace texproc::astc {
namespace {

struct Api {
  decltype(&astcenc_config_init) config_init = nullptr;
  decltype(&astcenc_context_alloc) context_alloc = nullptr;
  decltype(&astcenc_compress_image) compress_image = nullptr;
  decltype(&astcenc_compress_reset) compress_reset = nullptr;
  decltype(&astcenc_decompress_image) decompress_image = nullptr;
  decltype(&astcenc_decompress_reset) decompress_reset = nullptr;
  decltype(&astcenc_context_free) context_free = nullptr;
  decltype(&astcenc_get_block_info) get_block_info = nullptr;
  decltype(&astcenc_get_error_string) error_string = nullptr;
};

const Api& api() {
  static std::once_flag once;
  static Api a;
  static std::string why;
  std::call_once(once, [] {
    const char* env = std::getenv("TEXPROC_ASTCENC_LIBRARY");
    const std::string file = env && *env ? env : TEXPROC_ASTCENC_SONAME;
    void* h = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) {
      const char* e = dlerror();
      why = e ? e : file + ": dlopen failed";
      return;
    }
    auto sym = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(h, name));
      if (!fn && why.empty()) why = file + " has no " + name;
    };
    sym(a.config_init, "astcenc_config_init");
    sym(a.context_alloc, "astcenc_context_alloc");
    sym(a.compress_image, "astcenc_compress_image");
    sym(a.compress_reset, "astcenc_compress_reset");
    sym(a.decompress_image, "astcenc_decompress_image");
    sym(a.decompress_reset, "astcenc_decompress_reset");
    sym(a.context_free, "astcenc_context_free");
    sym(a.get_block_info, "astcenc_get_block_info");
    sym(a.error_string, "astcenc_get_error_string");
    if (!why.empty()) a = Api{};  // kept loaded, never used
  });
  if (!a.config_init) {
    throw Error(ErrorCode::unsupported,
                "ASTC is encoded and decoded by ARM's astc-encoder library, which could not be loaded (" + why +
                    "); install it (Debian: libastcenc3d) or name it in TEXPROC_ASTCENC_LIBRARY");
  }
  return a;
}

std::string failure(const char* what, astcenc_error e) {
  return std::string("astc-encoder: ") + what + ": " + (api().error_string ? api().error_string(e) : "error");
}

struct Key {
  astcenc_profile profile;
  unsigned block_x, block_y;
  float effort;
  unsigned flags;
  unsigned threads;
  bool operator==(const Key&) const = default;
};

// Contexts are costly to make (tables for the footprint and effort) and
// serve one image at a time: a run keeps the idle ones for the next image.
class ContextPool {
 public:
  ~ContextPool() {
    for (auto& [key, ctx] : idle_) api().context_free(ctx);
  }
  astcenc_context* acquire(const Key& k) {
    {
      std::lock_guard lock(mutex_);
      for (auto it = idle_.begin(); it != idle_.end(); ++it) {
        if (it->first == k) {
          astcenc_context* c = it->second;
          idle_.erase(it);
          return c;
        }
      }
    }
    const Api& a = api();
    astcenc_config config{};
    astcenc_error e = a.config_init(k.profile, k.block_x, k.block_y, 1, k.effort, k.flags, &config);
    if (e != ASTCENC_SUCCESS) throw Error(ErrorCode::bad_arguments, failure("configuration", e));
    astcenc_context* ctx = nullptr;
    e = a.context_alloc(&config, k.threads, &ctx);
    if (e != ASTCENC_SUCCESS) throw Error(ErrorCode::runtime, failure("context", e));
    return ctx;
  }
  void release(const Key& k, astcenc_context* ctx) {
    std::lock_guard lock(mutex_);
    idle_.emplace_back(k, ctx);
  }

 private:
  std::mutex mutex_;
  std::vector<std::pair<Key, astcenc_context*>> idle_;
};

ContextPool& pool() {
  static ContextPool p;
  return p;
}

class Lease {
 public:
  explicit Lease(const Key& k) : key_(k), ctx_(pool().acquire(k)) {}
  ~Lease() { pool().release(key_, ctx_); }
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;
  astcenc_context* get() const { return ctx_; }

 private:
  Key key_;
  astcenc_context* ctx_;
};

astcenc_profile profile_of(const FormatInfo& f, bool decoding) {
  if (f.is_float) return decoding ? ASTCENC_PRF_HDR : ASTCENC_PRF_HDR_RGB_LDR_A;
  return f.srgb ? ASTCENC_PRF_LDR_SRGB : ASTCENC_PRF_LDR;
}

// Runs fn(thread_index) on `threads` of texproc's workers at once.
void on_threads(unsigned threads, const std::function<void(unsigned)>& fn) {
  for_each_row_block(int(threads), 1, [&](int t0, int t1) {
    for (int t = t0; t < t1; ++t) fn(unsigned(t));
  });
}

// The input as the tightly packed RGBA image astc-encoder reads.
struct Packed {
  astcenc_type type = ASTCENC_TYPE_U8;
  std::vector<std::uint8_t> u8;
  std::vector<float> f32;
  void* data() { return type == ASTCENC_TYPE_U8 ? static_cast<void*>(u8.data()) : static_cast<void*>(f32.data()); }
};

// Gray fills RGB, missing alpha is 1; a two-channel normal map is X, Y.
Packed pack(const ConstImageView& img, bool hdr, bool normal_map) {
  Packed p;
  const std::size_t n = std::size_t(img.width) * img.height * 4;
  const int C = img.channels;
  // 8-bit LDR stays 8-bit; 16-bit and float go as float, keeping every bit
  // (astcenc's CLI reads a 16-bit PNG as 8-bit); LDR float is clamped to
  // [0, 1].
  p.type = !hdr && img.type == PixelType::u8 ? ASTCENC_TYPE_U8 : ASTCENC_TYPE_F32;
  if (p.type == ASTCENC_TYPE_U8) {
    p.u8.resize(n);
  } else {
    p.f32.resize(n);
  }
  // Which source channel feeds each of R, G, B, A (-1: constant 1).
  int src[4];
  if (normal_map && C == 2) {
    src[0] = src[2] = 0;
    src[1] = 1;
    src[3] = -1;
  } else if (C <= 2) {
    src[0] = src[1] = src[2] = 0;
    src[3] = C == 2 ? 1 : -1;
  } else {
    src[0] = 0;
    src[1] = 1;
    src[2] = 2;
    src[3] = C == 4 ? 3 : -1;
  }
  for_each_row_block(img.height, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const std::size_t o = std::size_t(y) * img.width * 4;
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < 4; ++c) {
          const std::size_t i = o + std::size_t(x) * 4 + c;
          const int s = src[c];
          switch (img.type) {
            case PixelType::u8: {
              const std::uint8_t v = s < 0 ? 255 : img.row<const std::uint8_t>(y)[x * C + s];
              if (p.type == ASTCENC_TYPE_U8)
                p.u8[i] = v;
              else
                p.f32[i] = float(v) / 255.0f;
              break;
            }
            case PixelType::u16: {
              const std::uint16_t v = s < 0 ? 65535 : img.row<const std::uint16_t>(y)[x * C + s];
              p.f32[i] = float(v) / 65535.0f;
              break;
            }
            case PixelType::f32: {
              float v = s < 0 ? 1.0f : img.row<const float>(y)[x * C + s];
              if (!hdr) v = std::clamp(v, 0.0f, 1.0f);
              p.f32[i] = v;
              break;
            }
          }
        }
    }
  });
  return p;
}

unsigned threads_now() { return unsigned(std::max(1, thread_limit())); }

}  // namespace

float effort_for(Quality q) {
  switch (q) {
    case Quality::fast:
      return ASTCENC_PRE_FAST;
    case Quality::normal:
      return ASTCENC_PRE_MEDIUM;
    case Quality::high:
      return ASTCENC_PRE_THOROUGH;
    case Quality::max:
      return ASTCENC_PRE_EXHAUSTIVE;
  }
  return ASTCENC_PRE_MEDIUM;
}

std::vector<std::uint8_t> encode(const ConstImageView& img, TexelFormat format, Quality q,
                                 const EncodeOptions& options) {
  const FormatInfo& fi = format_info(format);
  const float effort = options.astc_effort ? *options.astc_effort : effort_for(q);
  if (!(effort >= 0.0f && effort <= 100.0f))
    throw Error(ErrorCode::bad_arguments, "astc effort " + std::to_string(effort) + " is not in [0, 100]");
  if (options.normal_map && fi.is_float)
    throw Error(ErrorCode::bad_arguments, std::string("a normal map is LDR data: ") + fi.name + " is an HDR format");
  // An 8-bit RGBA image in packed rows is what astc-encoder reads: no copy.
  const bool as_is =
      !fi.is_float && img.type == PixelType::u8 && img.channels == 4 && img.row_stride == std::size_t(img.width) * 4;
  Packed packed = as_is ? Packed{} : pack(img, fi.is_float, options.normal_map);
  const Key key{profile_of(fi, false),
                unsigned(fi.block_width),
                unsigned(fi.block_height),
                effort,
                (options.normal_map ? ASTCENC_FLG_MAP_NORMAL : 0u) | ASTCENC_FLG_SELF_DECOMPRESS_ONLY,
                threads_now()};
  std::vector<std::uint8_t> out(image_bytes(format, std::uint32_t(img.width), std::uint32_t(img.height)));
  // astc-encoder's image type holds non-const slices; compressing only reads them.
  void* slice = as_is ? const_cast<void*>(img.data) : packed.data();
  astcenc_image image{unsigned(img.width), unsigned(img.height), 1, packed.type, &slice};
  // A normal map's X goes to RGB and Y to alpha (astc-encoder's rrrg, as its
  // CLI's -normal): the swizzle is the library's, which reads it per texel.
  const astcenc_swizzle swizzle = options.normal_map
                                      ? astcenc_swizzle{ASTCENC_SWZ_R, ASTCENC_SWZ_R, ASTCENC_SWZ_R, ASTCENC_SWZ_G}
                                      : astcenc_swizzle{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
  const Api& a = api();
  Lease ctx(key);
  std::atomic<int> error{ASTCENC_SUCCESS};
  on_threads(key.threads, [&](unsigned t) {
    const astcenc_error e = a.compress_image(ctx.get(), &image, &swizzle, out.data(), out.size(), t);
    if (e != ASTCENC_SUCCESS) error = e;
  });
  a.compress_reset(ctx.get());
  if (error != ASTCENC_SUCCESS) throw Error(ErrorCode::runtime, failure("compression", astcenc_error(error.load())));
  if (options.progress) options.progress(1.0);
  return out;
}

Image decode(const std::uint8_t* blocks, std::size_t size, int width, int height, TexelFormat format) {
  const FormatInfo& fi = format_info(format);
  if (size < image_bytes(format, std::uint32_t(width), std::uint32_t(height)))
    throw Error(ErrorCode::invalid_file, std::string(fi.name) + ": fewer bytes than the image's blocks");
  const Key key{profile_of(fi, true),        unsigned(fi.block_width),
                unsigned(fi.block_height),   0.0f,
                ASTCENC_FLG_DECOMPRESS_ONLY, threads_now()};
  Image out = Image::uninitialized(width, height, 4, fi.is_float ? PixelType::f32 : PixelType::u8);
  void* slice = out.data();
  astcenc_image image{unsigned(width), unsigned(height), 1, fi.is_float ? ASTCENC_TYPE_F32 : ASTCENC_TYPE_U8, &slice};
  const astcenc_swizzle swizzle{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
  const Api& a = api();
  Lease ctx(key);
  std::atomic<int> error{ASTCENC_SUCCESS};
  on_threads(key.threads, [&](unsigned t) {
    const astcenc_error e = a.decompress_image(ctx.get(), blocks, size, &image, &swizzle, t);
    if (e != ASTCENC_SUCCESS) error = e;
  });
  a.decompress_reset(ctx.get());
  if (error != ASTCENC_SUCCESS) throw Error(ErrorCode::runtime, failure("decompression", astcenc_error(error.load())));
  return out;
}

bool has_hdr_blocks(const std::uint8_t* blocks, std::size_t size, int block_width, int block_height) {
  const Key key{ASTCENC_PRF_HDR, unsigned(block_width), unsigned(block_height), 0.0f, ASTCENC_FLG_DECOMPRESS_ONLY, 1};
  const Api& a = api();
  Lease ctx(key);
  for (std::size_t o = 0; o + 16 <= size; o += 16) {
    // A constant-colour (void-extent) block: block mode bits 0-8 are
    // 1 1111 1100, bit 9 says FP16 (HDR) or UNORM16 (astc-encoder's block
    // info leaves is_hdr_block 0 for these).
    const std::uint8_t* b = blocks + o;
    if (b[0] == 0xFC && (b[1] & 0x01)) {
      if (b[1] & 0x02) return true;
      continue;
    }
    astcenc_block_info info;
    if (a.get_block_info(ctx.get(), blocks + o, &info) == ASTCENC_SUCCESS && info.is_hdr_block) return true;
  }
  return false;
}

}  // namespace texproc::astc
