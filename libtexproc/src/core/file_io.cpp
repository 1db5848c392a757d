#include "texproc/file_io.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path_);
  const std::string name = ".~" + p.filename().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                           std::to_string(counter++) + p.extension().string();
  temp_ = (p.parent_path() / name).string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    throw Error(ErrorCode::io, path_ + ": cannot write: " + std::strerror(err));
  }
  committed_ = true;
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    if (!out) throw Error(ErrorCode::io, path + ": cannot create: " + std::strerror(errno));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw Error(ErrorCode::io, path + ": write failed");
  }
  file.commit();
}

}  // namespace texproc
