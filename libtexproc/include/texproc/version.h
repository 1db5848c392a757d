#pragma once
namespace texproc {
// "MAJOR.MINOR.PATCH" of libtexproc.
const char* version_string();
}  // namespace texproc
