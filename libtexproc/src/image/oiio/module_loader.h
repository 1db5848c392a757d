// Loads texproc_oiio (oiio_module.h) on first use and wraps its C calls in
// texproc's types and errors. Where it looks, in order: $TEXPROC_OIIO_MODULE
// (a file; when set, nowhere else); beside the binary or shared library
// that holds libtexproc; ../lib/texproc/ from there; the build tree.
#pragma once

#include <string>
#include <vector>

#include "texproc/image.h"
#include "texproc/image_io.h"

namespace texproc::oiio {

bool loaded();
// Each throws Error: the module's own code and message, or Error{unsupported}
// naming `path` and every place looked in when the module cannot be loaded.
ImageFileInfo probe(const std::string& path);
void read(const std::string& path, const ImageView& into);
void write(const std::string& file, const std::string& path, const std::vector<ImageView>& levels, bool mip_file,
           const WriteOptions& options);

}  // namespace texproc::oiio
