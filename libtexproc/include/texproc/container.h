// texproc/container.h: DDS, KTX2, KTX1, PKM and .astc files.
//
// Writers lay files out exactly as the specifications say (docs/formats.md);
// readers check every field against the file size before using it and
// reject truncated files, trailing bytes, overflowing sizes, level counts
// that do not match and unknown formats with Error{invalid_file} (or
// Error{unsupported}) naming the file and the field. They never read out of
// bounds, whatever the bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "texproc/read_limits.h"
#include "texproc/texture.h"

namespace texproc {

enum class ContainerKind { dds, ktx2, ktx1, pkm, astc };
// From the extension: .dds, .ktx2, .ktx, .pkm, .astc. Throws Error{unsupported}.
ContainerKind container_for_path(const std::string& path);
const char* to_string(ContainerKind k);

enum class DdsHeader {
  automatic,  // legacy whenever a FourCC or masks say the format, else DX10
  dx9,        // legacy only (Error{unsupported} if the format needs DX10)
  dx10        // always the DX10 extended header
};

// In-memory encoders and decoders (`name` appears in error messages).
std::vector<std::uint8_t> encode_dds(const Texture& t, DdsHeader header = DdsHeader::automatic);
// zstd_level 1-22: each level Zstandard-supercompressed (scheme 2, as `ktx
// deflate --zstd` writes); 0: none.
std::vector<std::uint8_t> encode_ktx2(const Texture& t, const std::string& writer = "", int zstd_level = 0);
std::vector<std::uint8_t> encode_ktx1(const Texture& t);
std::vector<std::uint8_t> encode_pkm(const Texture& t);   // ETC1/ETC2 RGB, one level
std::vector<std::uint8_t> encode_astc(const Texture& t);  // ASTC, one level (astcenc's file)
Texture decode_dds(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& = {});
Texture decode_ktx2(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& = {});
Texture decode_ktx1(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& = {});
Texture decode_pkm(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& = {});
// .astc has no colour profile: UNORM, or SFLOAT when a block is HDR.
Texture decode_astc(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& = {});

// Files: written atomically; the container follows the extension.
// ktx2_zstd_level applies to .ktx2 outputs (encode_ktx2's zstd_level).
void write_texture(const std::string& path, const Texture& t, DdsHeader dds_header = DdsHeader::automatic,
                   int ktx2_zstd_level = 0);
Texture read_texture(const std::string& path, const ReadLimits& limits = {});
// How a KTX2 file stores its levels, for `info`: the supercompression scheme
// (0 none, 2 Zstandard, 3 zlib) and each level's bytes as stored and as
// inflated (equal without supercompression), level 0 first. Reads the
// header and the level index only; Error{invalid_file} if they do not fit
// the file.
struct Ktx2Storage {
  std::uint32_t scheme = 0;
  std::vector<std::uint64_t> stored_bytes, inflated_bytes;
};
Ktx2Storage ktx2_storage(const std::string& path);
const char* ktx2_scheme_name(std::uint32_t scheme);  // "none", "Zstandard", "zlib", "BasisLZ", "unknown"

// The container a file's first bytes (at least 12 where present) announce:
// false when they are none of DDS, KTX2, KTX1, PKM, .astc.
bool container_from_signature(const std::uint8_t* head, std::size_t n, ContainerKind& kind);
// True if the file starts with a DDS, KTX1, KTX2, PKM or .astc signature.
bool is_texture_container(const std::string& path);

// KTX2's Data Format Descriptor for a format, as libktx writes it.
std::vector<std::uint8_t> ktx2_dfd(TexelFormat f);

}  // namespace texproc
