// Shared objects of texproc's own that libtexproc loads with dlopen the
// first time they are needed (texproc_oiio for OpenImageIO's formats,
// texproc_ocio for OpenColorIO), so that a process that never needs them
// never maps those libraries and their dependencies at start-up.
#pragma once

#include <string>

namespace texproc {

struct ModuleSpec {
  const char* file;   // "texproc_oiio.so"
  const char* env;    // a variable that names the file to use instead (and nowhere else)
  const char* entry;  // the exported function that returns the module's table
  // Calls the entry `symbol` through its own type (a module's entry returns
  // its own table type; calling it through another is undefined behaviour,
  // which UBSan's function check reports) and returns the table.
  const void* (*call_entry)(void* symbol);
};

// Where it looks, in order: $env when set (and nowhere else); the folder
// $TEXPROC_MODULE_DIR when set (and nowhere else); beside the binary or
// shared library that holds libtexproc; the installed module folder
// relative to that (bin/ -> lib/<arch>/texproc/, as installed); the
// installed module folder of the prefix libtexproc was built for. Never a
// folder of the build tree: programs there (tests, benchmarks) set
// TEXPROC_MODULE_DIR. Returns what `entry` returns, or nullptr with `why`
// saying every place tried and what failed. Never unloads.
const void* load_module(const ModuleSpec& spec, std::string& why);

// The file load_module() would try first that exists (canonical path), or
// "" when there is none. Loads nothing.
std::string find_module(const ModuleSpec& spec);

}  // namespace texproc
