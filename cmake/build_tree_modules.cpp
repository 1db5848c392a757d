// Linked into the programs of the build tree that do not sit beside the
// runtime modules (tests, benchmarks, fuzzers): before main, point
// TEXPROC_MODULE_DIR at the build's module folder unless it is set already.
// libtexproc itself never looks into a build tree.
#include <cstdlib>

namespace {
const bool kModuleDirSet = [] { return ::setenv("TEXPROC_MODULE_DIR", TEXPROC_BUILD_MODULE_DIR, 0) == 0; }();
}  // namespace
