#include "texproc/version.h"
namespace texproc {
const char* version_string() { return TEXPROC_VERSION_STRING; }
}  // namespace texproc
