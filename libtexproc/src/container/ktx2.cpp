// KTX 2.0 (Khronos KTX File Format Specification 2.0): identifier, header,
// index, level index (level 0 first), DFD, key/value data (sorted, with
// KTXwriter), then the levels stored smallest first, each aligned to
// lcm(texel block bytes, 4). No supercompression.
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>

#include "container/bytes.h"
#include "format/format_names.h"
#include "container/streams.h"
#include "texproc/container.h"
#include "texproc/version.h"

namespace texproc {
namespace {

constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::size_t kHeaderEnd = 80;  // identifier 12 + header 36 + index 32

std::uint32_t level_alignment(const FormatInfo& i) { return std::lcm(std::uint32_t(i.block_bytes), 4u); }

}  // namespace

ByteWriter encode_ktx2_stream(const Texture& t, const std::string& writer, int zstd_level) {
  if (zstd_level < 0 || zstd_level > ZSTD_maxCLevel()) {
    throw Error(ErrorCode::bad_arguments, "Zstandard level " + std::to_string(zstd_level) + " (valid: 1 to " +
                                              std::to_string(ZSTD_maxCLevel()) + ")");
  }
  validate(t);
  const FormatInfo& info = format_info(t.format);
  ByteWriter w;
  w.raw(kIdentifier, 12);
  w.u32(info.vk_format);
  w.u32(std::uint32_t(info.type_size));
  w.u32(t.width);
  w.u32(t.height);
  w.u32(0);                                          // pixelDepth
  w.u32(t.is_array || t.layers > 1 ? t.layers : 0);  // layerCount: 0 for a non-array texture
  w.u32(t.faces);
  w.u32(t.levels);
  w.u32(zstd_level ? 2 : 0);  // supercompressionScheme: 2 Zstandard, 0 none
  const std::size_t index_at = w.size();
  w.zeros(32);  // dfd offset/length, kvd offset/length, sgd offset/length (u64)
  const std::size_t level_index_at = w.size();
  w.zeros(std::size_t(t.levels) * 24);

  const std::uint32_t dfd_offset = std::uint32_t(w.size());
  const std::vector<std::uint8_t> dfd = ktx2_dfd(t.format);
  w.raw(dfd.data(), dfd.size());

  // Key/value data: sorted by key (std::map), each entry padded to 4 bytes.
  std::map<std::string, std::string> kv;
  kv["KTXwriter"] = writer.empty() ? std::string("texproc ") + version_string() : writer;
  const std::uint32_t kvd_offset = std::uint32_t(w.size());
  for (const auto& [key, value] : kv) {
    const std::uint32_t len = std::uint32_t(key.size() + 1 + value.size() + 1);
    w.u32(len);
    w.raw(key.data(), key.size());
    w.u8(0);
    w.raw(value.data(), value.size());
    w.u8(0);
    w.pad_to(4);
  }
  const std::uint32_t kvd_length = std::uint32_t(w.size()) - kvd_offset;
  w.put_u32_at(index_at, dfd_offset);
  w.put_u32_at(index_at + 4, std::uint32_t(dfd.size()));
  w.put_u32_at(index_at + 8, kvd_offset);
  w.put_u32_at(index_at + 12, kvd_length);
  // sgd offset and length stay 0.

  // Supercompressed levels are not aligned (KTX2 specification, mip level array).
  const std::uint32_t align = zstd_level ? 1 : level_alignment(info);
  for (std::uint32_t l = t.levels; l-- > 0;) {
    w.pad_to(align);
    const std::uint64_t offset = w.size();
    std::uint64_t raw = 0;
    if (zstd_level) {
      // Within a level: layers, then faces (z slices, then rows); one frame for the level.
      std::vector<std::uint8_t> level;
      for (std::uint32_t a = 0; a < t.layers; ++a)
        for (std::uint32_t f = 0; f < t.faces; ++f)
          level.insert(level.end(), t.image(l, a, f).begin(), t.image(l, a, f).end());
      std::vector<std::uint8_t> packed(ZSTD_compressBound(level.size()));
      const std::size_t n = ZSTD_compress(packed.data(), packed.size(), level.data(), level.size(), zstd_level);
      if (ZSTD_isError(n)) throw Error(ErrorCode::runtime, std::string("Zstandard: ") + ZSTD_getErrorName(n));
      w.raw(packed.data(), n);
      raw = level.size();
    } else {
      for (std::uint32_t a = 0; a < t.layers; ++a)
        for (std::uint32_t f = 0; f < t.faces; ++f) {
          const auto& img = t.image(l, a, f);
          w.ref(img.data(), img.size());
        }
    }
    const std::uint64_t length = w.size() - offset;
    w.put_u64_at(level_index_at + 24 * l, offset);
    w.put_u64_at(level_index_at + 24 * l + 8, length);
    w.put_u64_at(level_index_at + 24 * l + 16, zstd_level ? raw : length);
  }
  return w;
}

std::vector<std::uint8_t> encode_ktx2(const Texture& t, const std::string& writer, int zstd_level) {
  return encode_ktx2_stream(t, writer, zstd_level).bytes();
}

namespace {

// A Zstandard (2) or zlib (3) level: exactly `want` bytes once inflated.
std::vector<std::uint8_t> supercompressed_level(const ByteReader& r, std::uint32_t level, std::uint32_t scheme,
                                                const std::uint8_t* data, std::uint64_t length, std::uint64_t want) {
  std::vector<std::uint8_t> out(want);
  const std::string where = "level " + std::to_string(level) + ": ";
  if (scheme == 2) {
    const unsigned long long size = ZSTD_getFrameContentSize(data, length);
    if (size == ZSTD_CONTENTSIZE_ERROR) r.fail(where + "not a Zstandard frame");
    if (size != ZSTD_CONTENTSIZE_UNKNOWN && size != want) {
      r.fail(where + "Zstandard frame of " + std::to_string(size) + " bytes (expected " + std::to_string(want) + ")");
    }
    const std::size_t n = ZSTD_decompress(out.data(), want, data, length);
    if (ZSTD_isError(n)) r.fail(where + "Zstandard data: " + ZSTD_getErrorName(n));
    if (n != want)
      r.fail(where + "Zstandard data inflates to " + std::to_string(n) + " bytes (expected " + std::to_string(want) +
             ")");
  } else {
    uLongf n = uLongf(want);
    const int rc = uncompress(out.data(), &n, data, uLong(length));
    if (rc != Z_OK || n != want) {
      r.fail(where + "zlib data " +
             (rc == Z_OK ? "inflates to " + std::to_string(n) + " bytes (expected " + std::to_string(want) + ")"
                         : std::string(rc == Z_BUF_ERROR ? "larger than the level" : "corrupt")));
    }
  }
  return out;
}

// The header's fields (KTX2 specification, "file structure").
struct Header {
  std::uint32_t vk, type_size, width, height, depth, layer_count, faces, level_count, scheme;
  std::uint32_t dfd_offset, dfd_length, kvd_offset, kvd_length;
  std::uint64_t sgd_offset, sgd_length;
};

Header read_header(const ByteReader& r, std::size_t size) {
  if (size < 12 || std::memcmp(r.at(0, 12, "identifier"), kIdentifier, 12) != 0)
    r.fail("not a KTX2 file (bad identifier)");
  Header h;
  h.vk = r.u32(12, "vkFormat");
  h.type_size = r.u32(16, "typeSize");
  h.width = r.u32(20, "pixelWidth");
  h.height = r.u32(24, "pixelHeight");
  h.depth = r.u32(28, "pixelDepth");
  h.layer_count = r.u32(32, "layerCount");
  h.faces = r.u32(36, "faceCount");
  h.level_count = r.u32(40, "levelCount");
  h.scheme = r.u32(44, "supercompressionScheme");
  h.dfd_offset = r.u32(48, "dfdByteOffset");
  h.dfd_length = r.u32(52, "dfdByteLength");
  h.kvd_offset = r.u32(56, "kvdByteOffset");
  h.kvd_length = r.u32(60, "kvdByteLength");
  h.sgd_offset = r.u64(64, "sgdByteOffset");
  h.sgd_length = r.u64(72, "sgdByteLength");
  return h;
}

// The header's values against the specification's validity rules and
// texproc's limits; the format they name.
const FormatInfo& check_header(const ByteReader& r, std::size_t size, const Header& h, const ReadLimits& limits) {
  const std::uint32_t vk = h.vk, type_size = h.type_size, width = h.width, height = h.height, depth = h.depth,
                      layer_count = h.layer_count, faces = h.faces, level_count = h.level_count, scheme = h.scheme;
  const std::uint32_t dfd_offset = h.dfd_offset, dfd_length = h.dfd_length;
  const std::uint64_t sgd_offset = h.sgd_offset, sgd_length = h.sgd_length;
  // Zstandard (2) and zlib (3) compress each level on its own; BasisLZ (1)
  // is a codec of its own, with global data.
  if (scheme == 1)
    r.unsupported(
        "supercompression scheme 1, BasisLZ (ETC1S), is not one texproc reads (valid: 0 none, 2 Zstandard, 3 zlib)");
  if (scheme > 3)
    r.unsupported("supercompression scheme " + std::to_string(scheme) + " (valid: 0 none, 2 Zstandard, 3 zlib)");
  const FormatInfo* fi = find_format_by_vk(vk);
  if (!fi) {
    // Name what it is: Basis Universal's formats have vkFormat 0 and say which in the DFD's colour model.
    std::string what = vk_format_name(vk);
    if (vk == 0 && dfd_length >= 16 && std::uint64_t(dfd_offset) + 16 <= size) {
      const std::uint32_t model = r.u32(dfd_offset + 12, "DFD colour model") & 0xFF;
      if (model == 166) what = "UASTC, Basis Universal";
      if (model == 163) what = "ETC1S, Basis Universal";
    }
    r.unsupported("vkFormat " + std::to_string(vk) + (what.empty() ? "" : " (" + what + ")") +
                  " is not one texproc reads");
  }
  if (type_size != std::uint32_t(fi->type_size)) {
    r.fail("typeSize " + std::to_string(type_size) + " (valid for " + fi->name + ": " + std::to_string(fi->type_size) +
           ")");
  }
  if (width == 0 || height == 0) r.fail("zero pixelWidth or pixelHeight (1D textures are not supported)");
  if (width > limits.max_texture_dimension || height > limits.max_texture_dimension) {
    r.unsupported(std::to_string(width) + "x" + std::to_string(height) + " is larger than " +
                  std::to_string(limits.max_texture_dimension) + " texels a side");
  }
  if (depth != 0) r.unsupported("3D textures are not supported");
  if (faces != 1 && faces != 6) r.fail("faceCount " + std::to_string(faces) + " (valid: 1, 6)");
  if (faces == 6 && width != height) r.fail("cubemap faces are not square");
  if (layer_count > limits.max_layers) r.fail("layerCount " + std::to_string(layer_count));
  std::uint32_t max_levels = 1;
  for (std::uint32_t m = std::max(width, height); m > 1; m >>= 1) ++max_levels;
  if (level_count > max_levels) {
    r.fail("levelCount " + std::to_string(level_count) + " is more than a " + std::to_string(width) + "x" +
           std::to_string(height) + " texture has (" + std::to_string(max_levels) + ")");
  }
  if (level_count == 0) r.unsupported("levelCount 0 (generate mipmaps at load) is not supported");
  if (sgd_offset != 0 || sgd_length != 0) {
    r.fail("supercompression global data (sgdByteLength " + std::to_string(sgd_length) + ") with scheme " +
           std::to_string(scheme) + ", which has none");
  }
  return *fi;
}

// The data format descriptor: the one this format has (texproc reads what
// it writes, and what libktx writes for the same VkFormat), or another
// writer's whose transfer function agrees with the format.
void check_dfd(const ByteReader& r, const Header& h, const FormatInfo* fi) {
  const std::uint32_t dfd_offset = h.dfd_offset, dfd_length = h.dfd_length, level_count = h.level_count;
  const std::vector<std::uint8_t> want_dfd = ktx2_dfd(fi->format);
  if (dfd_offset < kHeaderEnd + 24ull * level_count) r.fail("dfdByteOffset overlaps the level index");
  const std::uint8_t* dfd = r.at(dfd_offset, dfd_length, "data format descriptor");
  if (dfd_length < 4 || r.u32(dfd_offset, "dfdTotalSize") != dfd_length)
    r.fail("dfdTotalSize does not match dfdByteLength");
  if (dfd_length != want_dfd.size() || std::memcmp(dfd, want_dfd.data(), dfd_length) != 0) {
    // Accept another writer's descriptor only if its transfer function agrees with the format.
    if (dfd_length < 28) r.fail("data format descriptor too short");
    const std::uint32_t transfer = (r.u32(dfd_offset + 12, "DFD transfer") >> 16) & 0xFF;
    if ((transfer == 2) != fi->srgb) r.fail("DFD transfer function contradicts vkFormat");
  }
}

// The key/value data: every entry's length inside the block, keys
// NUL-terminated; values without their trailing NULs.
std::map<std::string, std::string> read_key_values(const ByteReader& r, const Header& h) {
  const std::uint32_t kvd_offset = h.kvd_offset, kvd_length = h.kvd_length, dfd_offset = h.dfd_offset,
                      dfd_length = h.dfd_length;
  std::map<std::string, std::string> kv;
  if (!kvd_length) return kv;
  r.at(kvd_offset, kvd_length, "key/value data");
  // Walk the entries: every length must stay inside the block.
  std::uint64_t p = kvd_offset, end = std::uint64_t(kvd_offset) + kvd_length;
  if (kvd_offset < dfd_offset + std::uint64_t(dfd_length)) r.fail("kvdByteOffset overlaps the data format descriptor");
  while (p < end) {
    if (end - p < 4) {
      r.fail("key/value data: " + std::to_string(end - p) + " bytes left at byte " + std::to_string(p) +
             ", fewer than an entry's 4-byte keyAndValueByteLength");
    }
    const std::uint32_t len = r.u32(p, "key/value length");
    if (len > end - p - 4) {
      r.fail("key/value entry at byte " + std::to_string(p) + ": keyAndValueByteLength " + std::to_string(len) +
             " runs past the key/value data (" + std::to_string(end - p - 4) + " bytes left)");
    }
    const std::uint8_t* entry = r.at(p + 4, len, "key/value entry");
    const void* nul = std::memchr(entry, 0, len);
    if (len < 2 || !nul || nul == entry) {
      r.fail("key/value entry at byte " + std::to_string(p) + ": the key is not a non-empty NUL-terminated string");
    }
    {
      const auto* key_end = static_cast<const std::uint8_t*>(nul);
      std::string value(reinterpret_cast<const char*>(key_end + 1), reinterpret_cast<const char*>(entry + len));
      while (!value.empty() && value.back() == '\0') value.pop_back();
      kv[std::string(reinterpret_cast<const char*>(entry), reinterpret_cast<const char*>(key_end))] = value;
    }
    const std::uint64_t next = p + 4 + ((std::uint64_t(len) + 3) & ~std::uint64_t(3));
    if (next > end)
      r.fail("key/value entry at byte " + std::to_string(p) + ": its padding runs past the key/value data");
    p = next;
  }
  return kv;
}

// Each level's images from the level index (inflated where supercompressed);
// the levels in place, aligned, without overlap, with nothing but alignment
// padding between them, and nothing after the last.
void read_levels(const ByteReader& r, std::size_t size, const Header& h, const FormatInfo* fi, Texture& t,
                 const ReadLimits& limits) {
  const std::uint32_t level_count = h.level_count, scheme = h.scheme, dfd_offset = h.dfd_offset,
                      dfd_length = h.dfd_length, kvd_offset = h.kvd_offset, kvd_length = h.kvd_length;
  const std::uint64_t sgd_offset = h.sgd_offset, sgd_length = h.sgd_length;
  // Supercompressed levels need no alignment (KTX2 specification, "mip level array").
  const std::uint32_t align = scheme ? 1 : level_alignment(*fi);
  // Levels lie after every other block, in place, without overlap, with
  // nothing but alignment padding between them.
  const std::uint64_t metadata_end =
      std::max<std::uint64_t>({kHeaderEnd + 24ull * level_count, std::uint64_t(dfd_offset) + dfd_length,
                               kvd_length ? std::uint64_t(kvd_offset) + kvd_length : 0, sgd_offset + sgd_length});
  if (scheme == 2 || scheme == 3) {  // what the levels inflate to, before any is inflated
    std::uint64_t total = 0;
    for (std::uint32_t l = 0; l < level_count; ++l) {
      total += image_bytes(t.format, t.level_width(l), t.level_height(l)) * t.layers * t.faces;
    }
    if (!limits.headers_only && total > limits.max_inflated_bytes) {
      r.fail("its supercompressed levels inflate to " + std::to_string(total) + " bytes, over the limit of " +
             std::to_string(limits.max_inflated_bytes) + " (TEXPROC_MAX_TEXTURE_BYTES raises it)");
    }
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> placed;  // offset, level
  std::vector<std::uint64_t> placed_length(level_count);
  std::uint64_t covered = 0;
  for (std::uint32_t l = 0; l < level_count; ++l) {
    const std::uint64_t offset = r.u64(kHeaderEnd + 24ull * l, "level byteOffset");
    const std::uint64_t length = r.u64(kHeaderEnd + 24ull * l + 8, "level byteLength");
    const std::uint64_t ulength = r.u64(kHeaderEnd + 24ull * l + 16, "level uncompressedByteLength");
    const std::uint64_t image = image_bytes(t.format, t.level_width(l), t.level_height(l));
    const std::uint64_t want = image * t.layers * t.faces;
    if (scheme == 0 && length != want) {
      r.fail("level " + std::to_string(l) + " byteLength " + std::to_string(length) + " (expected " +
             std::to_string(want) + ")");
    }
    if (ulength != want) {
      r.fail("level " + std::to_string(l) + " uncompressedByteLength " + std::to_string(ulength) + " (expected " +
             std::to_string(want) + (scheme ? ")" : " without supercompression)"));
    }
    if (offset % align) {
      r.fail("level " + std::to_string(l) + " byteOffset " + std::to_string(offset) + " is not aligned to " +
             std::to_string(align) + " bytes");
    }
    if (offset < metadata_end) {
      r.fail("level " + std::to_string(l) + " byteOffset " + std::to_string(offset) +
             " lies inside the header, index, descriptor or key/value data (they end at byte " +
             std::to_string(metadata_end) + ")");
    }
    placed.push_back({offset, l});
    const std::uint8_t* stored = r.at(offset, length, "level data");
    covered = std::max(covered, offset + length);
    placed_length[l] = length;
    if (limits.headers_only) continue;
    std::vector<std::uint8_t> inflated;
    const std::uint8_t* level_data = stored;
    if (scheme == 2 || scheme == 3) {
      inflated = supercompressed_level(r, l, scheme, stored, length, want);
      level_data = inflated.data();
    }
    std::uint64_t p = 0;
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f) {
        t.image(l, a, f).assign(level_data + p, level_data + p + image);
        p += image;
      }
    placed_length[l] = length;
  }
  std::sort(placed.begin(), placed.end());
  std::uint64_t prev_end = metadata_end;
  for (const auto& [offset, l] : placed) {
    if (offset < prev_end) r.fail("level " + std::to_string(l) + " overlaps another level");
    if (offset - prev_end >= std::max<std::uint64_t>(align, 4)) {
      r.fail(std::to_string(offset - prev_end) + " bytes before level " + std::to_string(l) +
             " that no level index entry covers (levelCount " + std::to_string(level_count) +
             "; only alignment padding may lie between levels)");
    }
    prev_end = offset + placed_length[l];
  }
  if (covered != size) r.fail(std::to_string(size - covered) + " trailing bytes after the last level");
}

// KTXswizzle and KTXorientation: texproc hands texels over as stored, rows
// top to bottom.
void apply_key_values(const ByteReader& r, const std::map<std::string, std::string>& kv, const FormatInfo* fi,
                      Texture& t) {
  // KTXswizzle: texproc hands texels over as stored, so only the identity is honest.
  if (auto sw = kv.find("KTXswizzle"); sw != kv.end() && sw->second != "rgba") {
    r.unsupported("KTXswizzle '" + sw->second + "' (texproc reads texels as stored: 'rgba' only)");
  }
  // KTXorientation: rows top to bottom ("rd", the default) as texproc keeps
  // them; uncompressed "ru" files are flipped on read, block formats refused.
  if (auto o = kv.find("KTXorientation"); o != kv.end()) {
    const std::string& v = o->second;
    if (v.size() < 2 || v[0] != 'r' || (v[1] != 'd' && v[1] != 'u')) {
      r.unsupported("KTXorientation '" + v + "' (texproc reads 'rd' and, uncompressed, 'ru')");
    }
    if (v[1] == 'u') {
      if (fi->compressed)
        r.unsupported("KTXorientation 'ru' on block-compressed " + std::string(fi->name) + " (rows bottom to top)");
      for (std::uint32_t l = 0; l < t.levels; ++l) {
        const std::size_t row = std::size_t(t.level_width(l)) * std::uint32_t(fi->block_bytes);
        const std::uint32_t h = t.level_height(l);
        for (std::uint32_t a = 0; a < t.layers; ++a)
          for (std::uint32_t f = 0; f < t.faces; ++f) {
            auto& img = t.image(l, a, f);
            for (std::uint32_t y = 0; y < h / 2; ++y)
              std::swap_ranges(img.begin() + std::ptrdiff_t(y * row), img.begin() + std::ptrdiff_t((y + 1) * row),
                               img.begin() + std::ptrdiff_t((h - 1 - y) * row));
          }
      }
    }
  }
}

}  // namespace

Texture decode_ktx2(const std::uint8_t* data, std::size_t size, const std::string& name, const ReadLimits& limits) {
  ByteReader r(data, size, name);
  const Header h = read_header(r, size);
  const FormatInfo* fi = &check_header(r, size, h, limits);
  check_dfd(r, h, fi);
  const std::map<std::string, std::string> kv = read_key_values(r, h);
  Texture t;
  t.format = fi->format;
  t.width = h.width;
  t.height = h.height;
  t.levels = h.level_count;
  t.faces = h.faces;
  t.layers = std::max(h.layer_count, 1u);
  t.is_array = h.layer_count > 0;
  t.images.resize(std::size_t(t.levels) * t.layers * t.faces);
  read_levels(r, size, h, fi, t, limits);
  apply_key_values(r, kv, fi, t);
  return t;
}

const char* ktx2_scheme_name(std::uint32_t scheme) {
  switch (scheme) {
    case 0:
      return "none";
    case 1:
      return "BasisLZ";
    case 2:
      return "Zstandard";
    case 3:
      return "zlib";
    default:
      return "unknown";
  }
}

Ktx2Storage ktx2_storage(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::io, path + ": cannot open");
  std::uint8_t head[80] = {};
  in.read(reinterpret_cast<char*>(head), sizeof head);
  if (in.gcount() != sizeof head || std::memcmp(head, "\xABKTX 20\xBB\r\n\x1A\n", 12) != 0) {
    throw Error(ErrorCode::invalid_file, path + ": not a KTX2 file");
  }
  auto u32 = [](const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
  };
  auto u64 = [&](const std::uint8_t* p) { return std::uint64_t(u32(p)) | std::uint64_t(u32(p + 4)) << 32; };
  Ktx2Storage s;
  s.scheme = u32(head + 44);
  const std::uint32_t levels = std::max<std::uint32_t>(1, u32(head + 40));
  if (levels > 32)
    throw Error(ErrorCode::invalid_file, path + ": levelCount " + std::to_string(levels) + " (at most 32)");
  std::vector<std::uint8_t> index(std::size_t(levels) * 24);
  in.read(reinterpret_cast<char*>(index.data()), std::streamsize(index.size()));
  if (std::size_t(in.gcount()) != index.size())
    throw Error(ErrorCode::invalid_file, path + ": the level index is cut short");
  for (std::uint32_t l = 0; l < levels; ++l) {
    s.stored_bytes.push_back(u64(index.data() + 24 * l + 8));
    s.inflated_bytes.push_back(u64(index.data() + 24 * l + 16));
  }
  return s;
}

}  // namespace texproc
