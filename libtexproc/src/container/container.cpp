// Container dispatch: by extension for writing, by signature for reading.
#include <cstring>
#include <filesystem>
#include <fstream>

#include "container/streams.h"
#include "core/fd_writer.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/file_io.h"

namespace fs = std::filesystem;

namespace texproc {

ContainerKind container_for_path(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (e == ".dds") return ContainerKind::dds;
  if (e == ".ktx2") return ContainerKind::ktx2;
  if (e == ".ktx") return ContainerKind::ktx1;
  if (e == ".pkm") return ContainerKind::pkm;
  throw Error(ErrorCode::unsupported, path + ": not a texture container extension (valid: .dds, .ktx2, .ktx, .pkm)");
}

const char* to_string(ContainerKind k) {
  switch (k) {
    case ContainerKind::dds: return "dds";
    case ContainerKind::ktx2: return "ktx2";
    case ContainerKind::ktx1: return "ktx1";
    case ContainerKind::pkm: return "pkm";
  }
  return "?";
}

void write_texture(const std::string& path, const Texture& t, DdsHeader dds_header, int ktx2_zstd_level) {
  ByteWriter stream;
  try {
    switch (container_for_path(path)) {
      case ContainerKind::dds: stream = encode_dds_stream(t, dds_header); break;
      case ContainerKind::ktx2: stream = encode_ktx2_stream(t, "", ktx2_zstd_level); break;
      case ContainerKind::ktx1: stream = encode_ktx1_stream(t); break;
      case ContainerKind::pkm: stream = encode_pkm_stream(t); break;
    }
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (msg.rfind(path, 0) == 0) throw;
    throw Error(e.code(), path + ": " + msg);
  }
  // Headers and images go to the file as they lie: no copy of the texture.
  AtomicFile file(path);
  FdWriter out(file.temp_path(), path);
  stream.write_to([&](const std::uint8_t* p, std::size_t n) { out.write(p, n); });
  out.close();
  file.commit();
}

namespace {
std::vector<std::uint8_t> slurp(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(ErrorCode::io, path + ": no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::io, path + ": cannot open");
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
}  // namespace

bool is_texture_container(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[12] = {};
  in.read(head, 12);
  const auto n = in.gcount();
  if (n >= 4 && (std::memcmp(head, "DDS ", 4) == 0 || std::memcmp(head, "PKM ", 4) == 0)) return true;
  return n >= 12 && std::memcmp(head, "\xABKTX ", 5) == 0;
}

Texture read_texture(const std::string& path, const ReadLimits& limits) {
  const std::vector<std::uint8_t> b = slurp(path);
  if (b.size() >= 4 && std::memcmp(b.data(), "DDS ", 4) == 0) return decode_dds(b.data(), b.size(), path, limits);
  if (b.size() >= 4 && std::memcmp(b.data(), "PKM ", 4) == 0) return decode_pkm(b.data(), b.size(), path, limits);
  if (b.size() >= 12 && std::memcmp(b.data(), "\xABKTX 20\xBB", 8) == 0) return decode_ktx2(b.data(), b.size(), path, limits);
  if (b.size() >= 12 && std::memcmp(b.data(), "\xABKTX 11\xBB", 8) == 0) return decode_ktx1(b.data(), b.size(), path, limits);
  throw Error(ErrorCode::invalid_file, path + ": not a DDS, KTX2, KTX1 or PKM file (unknown signature)");
}

}  // namespace texproc
