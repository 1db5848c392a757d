// A file written with POSIX calls whose every failure (a short write, ENOSPC,
// EIO, a failed close) throws Error{io} naming `path` and the OS error. The
// image writers write temporary files through it; AtomicFile renames them.
#pragma once

#include <cstddef>
#include <string>

namespace texproc {

class FdWriter {
 public:
  FdWriter(const std::string& file, const std::string& path);  // creates (truncates) `file`
  ~FdWriter();                                                 // closes, ignoring errors, if close() was not called
  FdWriter(const FdWriter&) = delete;
  FdWriter& operator=(const FdWriter&) = delete;
  void write(const void* data, std::size_t n);
  void close();  // flushes the buffer and closes, checking both

 private:
  void flush();
  void write_all(const void* data, std::size_t n);
  int fd_ = -1;
  std::string path_;
  std::string buffer_;
};

}  // namespace texproc
