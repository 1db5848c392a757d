#include "core/fd_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "texproc/error.h"

namespace texproc {
namespace {
constexpr std::size_t kBuffer = std::size_t(1) << 20;
[[noreturn]] void fail(const std::string& path, int err) {
  throw Error(ErrorCode::io, path + ": cannot write: " + std::strerror(err));
}
}  // namespace

FdWriter::FdWriter(const std::string& file, const std::string& path) : path_(path) {
  fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) fail(path_, errno);
}

FdWriter::~FdWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void FdWriter::write_all(const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  std::size_t left = size;
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path_, errno);
    if (n == 0) fail(path_, EIO);
    p += n;
    left -= std::size_t(n);
  }
}

void FdWriter::flush() {
  write_all(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void FdWriter::write(const void* data, std::size_t n) {
  if (buffer_.size() + n > kBuffer) {
    flush();
    if (n >= kBuffer) return write_all(data, n);  // large blocks go straight to the file
  }
  buffer_.append(static_cast<const char*>(data), n);
}

void FdWriter::close() {
  flush();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(path_, errno);
}

}  // namespace texproc
