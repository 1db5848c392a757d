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
  // Renames temp_path() to path(). Under CommitPolicy::keep_identical, when
  // path() already holds exactly these bytes, removes temp_path() instead and
  // leaves path() untouched (its time stamp too). Returns whether path() was
  // replaced. Throws Error{io} on failure.
  bool commit();

 private:
  std::string path_, temp_;
  bool committed_ = false;
};

// Process-wide: what commit() does when the output exists with the same
// bytes. replace (the default) renames anyway; keep_identical leaves the old
// file, so build systems that check time stamps (Ninja's restat, Make) see no
// change. Set it before work starts, not while files are being written.
enum class CommitPolicy { replace, keep_identical };
void set_commit_policy(CommitPolicy policy);
CommitPolicy commit_policy();

// Writes `bytes` to `path` atomically. Throws Error{io}.
void write_file_atomic(const std::string& path, const std::string& bytes);

}  // namespace texproc
