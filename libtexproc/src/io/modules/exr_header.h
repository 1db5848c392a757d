// texproc_exr: the check of an OpenEXR file's headers before OpenEXR opens
// it (exr_header.cpp says why).
#pragma once

#include <string>

namespace texproc::exr {

// Throws texproc::Error{invalid_file} naming `path` for a header whose
// declared sizes OpenEXR would allocate past what the file can hold;
// Error{io} when it cannot be opened. A file too short to have a header
// passes (OpenEXR says what is wrong with it).
void check_header(const std::string& path);

}  // namespace texproc::exr
