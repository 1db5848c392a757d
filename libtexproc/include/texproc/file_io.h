// texproc/file_io.h: atomic output files.
#pragma once

#include <string>

namespace texproc {

// Write to temp_path(), then commit() renames it over `path` in one step, so a
// reader (or a build system) never sees a half-written file. If the object is
// destroyed without commit() (an exception, an error), the temporary file is
// removed and `path` is left as it was.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // In the same folder as path() (so the rename cannot cross file systems),
  // hidden, unique to this process, ending in path()'s extension.
  const std::string& temp_path() const { return temp_; }
  // Renames temp_path() to path(). Throws Error{io} on failure.
  void commit();

 private:
  std::string path_, temp_;
  bool committed_ = false;
};

// Writes `bytes` to `path` atomically. Throws Error{io}.
void write_file_atomic(const std::string& path, const std::string& bytes);

}  // namespace texproc
