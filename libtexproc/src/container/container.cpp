// Container dispatch: by extension for writing, by signature for reading.
#include <cstring>
#include <filesystem>
#include <cstdlib>
#include <fstream>

#include "container/streams.h"
#include "core/fd_writer.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc {

ContainerKind container_for_path(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (e == ".dds") return ContainerKind::dds;
  if (e == ".ktx2") return ContainerKind::ktx2;
  if (e == ".ktx") return ContainerKind::ktx1;
  if (e == ".pkm") return ContainerKind::pkm;
  if (e == ".astc") return ContainerKind::astc;
  throw Error(ErrorCode::unsupported,
              path + ": not a texture container extension (valid: .dds, .ktx2, .ktx, .pkm, .astc)");
}

const char* to_string(ContainerKind k) {
  switch (k) {
    case ContainerKind::dds:
      return "dds";
    case ContainerKind::ktx2:
      return "ktx2";
    case ContainerKind::ktx1:
      return "ktx1";
    case ContainerKind::pkm:
      return "pkm";
    case ContainerKind::astc:
      return "astc";
  }
  return "?";
}

void write_texture(const std::string& path, const Texture& t, DdsHeader dds_header, int ktx2_zstd_level) {
  ByteWriter stream;
  try {
    switch (container_for_path(path)) {
      case ContainerKind::dds:
        stream = encode_dds_stream(t, dds_header);
        break;
      case ContainerKind::ktx2:
        stream = encode_ktx2_stream(t, "", ktx2_zstd_level);
        break;
      case ContainerKind::ktx1:
        stream = encode_ktx1_stream(t);
        break;
      case ContainerKind::pkm:
        stream = encode_pkm_stream(t);
        break;
      case ContainerKind::astc:
        stream = encode_astc_stream(t);
        break;
    }
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (msg.rfind(path, 0) == 0) throw;
    throw Error(e.code(), path + ": " + msg);
  }
  // What texproc writes it reads back: nothing past the read limits.
  const ReadLimits limits;
  if (t.width > limits.max_texture_dimension || t.height > limits.max_texture_dimension) {
    throw Error(ErrorCode::unsupported, path + ": " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                            " is over " + std::to_string(limits.max_texture_dimension) +
                                            " texels a side, the most a texture may have (Direct3D 11 and 12, and "
                                            "texproc's readers): resize the image");
  }
  if (t.layers > limits.max_layers) {
    throw Error(ErrorCode::unsupported, path + ": " + std::to_string(t.layers) + " layers, over the limit of " +
                                            std::to_string(limits.max_layers));
  }
  // Headers and images go to the file as they lie: no copy of the texture.
  AtomicFile file(path);
  FdWriter out(file.temp_path(), path);
  stream.write_to([&](const std::uint8_t* p, std::size_t n) { out.write(p, n); });
  out.close();
  file.commit();
}

namespace {
// A texture file's bytes: a regular file, or a pipe up to 1 GiB; devices
// (/dev/zero would never end) and folders are refused.
std::vector<std::uint8_t> slurp(const std::string& path) {
  constexpr std::size_t kMaxStreamBytes = std::size_t(1) << 30;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw Error(ErrorCode::io, path + ": no such file");
  if (!fs::is_regular_file(st) && st.type() != fs::file_type::fifo) {
    throw Error(ErrorCode::invalid_file, path + ": not a regular file (a file or a pipe is read)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::io, path + ": cannot open");
  std::vector<std::uint8_t> bytes;
  if (fs::is_regular_file(st)) bytes.reserve(std::size_t(fs::file_size(path, ec)));
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    if (bytes.size() + std::size_t(in.gcount()) > kMaxStreamBytes && !fs::is_regular_file(st)) {
      throw Error(ErrorCode::io, path + ": more than 1024 MiB from a pipe: refused");
    }
    bytes.insert(bytes.end(), buf, buf + in.gcount());
  }
  if (in.bad()) throw Error(ErrorCode::io, path + ": cannot read");
  return bytes;
}
}  // namespace

bool container_from_signature(const std::uint8_t* b, std::size_t n, ContainerKind& kind) {
  auto starts = [&](const char* sig, std::size_t len) { return n >= len && std::memcmp(b, sig, len) == 0; };
  if (starts("DDS ", 4))
    kind = ContainerKind::dds;
  else if (starts("PKM ", 4))
    kind = ContainerKind::pkm;
  else if (n >= 12 && starts("\xABKTX 20\xBB", 8))
    kind = ContainerKind::ktx2;  // the reader checks the rest
  else if (n >= 12 && starts("\xABKTX 11\xBB", 8))
    kind = ContainerKind::ktx1;
  else if (starts("\x13\xAB\xA1\x5C", 4))
    kind = ContainerKind::astc;
  else
    return false;
  return true;
}

bool is_texture_container(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[12] = {};
  in.read(head, 12);
  ContainerKind kind;
  return container_from_signature(reinterpret_cast<const std::uint8_t*>(head), std::size_t(in.gcount()), kind);
}

Texture read_texture(const std::string& path, const ReadLimits& limits) {
  const std::vector<std::uint8_t> b = slurp(path);
  ContainerKind kind;
  if (!container_from_signature(b.data(), b.size(), kind))
    throw Error(ErrorCode::invalid_file, path + ": not a DDS, KTX2, KTX1, PKM or .astc file (unknown signature)");
  switch (kind) {
    case ContainerKind::dds:
      return decode_dds(b.data(), b.size(), path, limits);
    case ContainerKind::ktx2:
      return decode_ktx2(b.data(), b.size(), path, limits);
    case ContainerKind::ktx1:
      return decode_ktx1(b.data(), b.size(), path, limits);
    case ContainerKind::pkm:
      return decode_pkm(b.data(), b.size(), path, limits);
    case ContainerKind::astc:
      return decode_astc(b.data(), b.size(), path, limits);
  }
  return {};
}

}  // namespace texproc
