// The boundary between libtexproc and texproc_ocio, the module that holds
// OpenColorIO (loaded on first use: only a colour space outside the
// built-in linear and sRGB needs it). Plain C types only.
#pragma once

#include <stddef.h>

extern "C" {

enum { TP_OCIO_MODULE_ABI = 1 };

struct TpOcioModule {
  int abi;
  // A transform between `space` and the active config's scene_linear role,
  // or null with a texproc::ErrorCode in *code and the message in err.
  // config_path gets the config file it came from ("" for the built-in one).
  void* (*create)(const char* space, char* config_path, size_t path_size, int* code, char* err, size_t err_size);
  // In place on `width` pixels of `channels` (1-4; grey goes through as
  // R=G=B, alpha is untouched). Thread-safe.
  void (*to_linear)(const void* transform, float* pixels, int channels, int width);
  void (*from_linear)(const void* transform, float* pixels, int channels, int width);
  void (*destroy)(void* transform);
  // The active config's colour-space names, NUL-separated, into out; returns
  // the bytes needed (call again with a larger buffer if it is larger), or
  // -1 with the message in err when the config cannot be loaded.
  long (*names)(char* out, size_t size, int* code, char* err, size_t err_size);
};

const struct TpOcioModule* texproc_ocio_module(void);
}
