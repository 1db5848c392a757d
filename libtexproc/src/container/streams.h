// The containers' writers as ByteWriter streams that reference the texture's
// images instead of copying them (write_texture sends them to the file as
// they are; encode_* concatenate them).
#pragma once

#include <string>

#include "container/bytes.h"
#include "texproc/container.h"

namespace texproc {

ByteWriter encode_dds_stream(const Texture& t, DdsHeader header);
ByteWriter encode_ktx2_stream(const Texture& t, const std::string& writer, int zstd_level = 0);
ByteWriter encode_ktx1_stream(const Texture& t);
ByteWriter encode_pkm_stream(const Texture& t);
ByteWriter encode_astc_stream(const Texture& t);

}  // namespace texproc
