// Per-file change tracking for `texproc build`: a small JSON file beside a
// recipe's outputs (".RECIPE_FILE_NAME.state") records, for each file a
// recipe cooked, the signature of the job settings it was cooked with, the
// tool digest, and the size, time stamp and content hash of its inputs and
// outputs. A file is rebuilt when one of those changed, not when the recipe
// file's time stamp did: editing one job reruns only that job's files, and
// a comment or another job's line reruns nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "batch.h"

namespace texproc::cli {

// An exclusive lock (flock) on `path`, created if missing, held while the
// object lives: builds that share an output folder (the shares of a job
// array) update its records one at a time. Throws Error{io}.
class FileLock {
 public:
  explicit FileLock(const std::string& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_ = -1;
};

class BuildState {
 public:
  // Loads `root`/.NAME.state if present (a damaged file counts as empty:
  // every file is rebuilt, never skipped on a guess).
  BuildState(const std::filesystem::path& root, const std::string& recipe_file_name);

  // "" when the file's outputs are up to date for settings `signature`,
  // else why it is rebuilt: "new", "job settings changed", "texproc
  // changed", "output missing: X", "output changed: X", "inputs changed",
  // "input changed: X". An input whose time stamp moved but whose bytes did
  // not is up to date (its new stamp is recorded by save()).
  std::string why_rebuild(const FileReport& r, const std::string& signature);
  // Records a file cooked with `signature` (its inputs hashed now).
  void record(const FileReport& r, const std::string& signature);
  // Writes the state (atomically), merged over what another process that
  // shares the folder may have written since this one loaded it (hold a
  // FileLock on the folder's lock file around it).
  void save();

  const std::filesystem::path& file() const { return file_; }
  bool dirty() const { return !changed_.empty(); }

 private:
  struct Stamp {
    std::string path;  // relative to the root where possible
    std::uintmax_t size = 0;
    std::int64_t mtime_ns = 0;
    std::string hash;  // inputs only
  };
  struct Entry {
    std::string signature, tool;
    std::vector<Stamp> inputs, outputs;
  };
  std::string relative(const std::string& path) const;
  std::string absolute(const std::string& rel) const;
  static std::map<std::string, Entry> load(const std::filesystem::path& file);

  std::filesystem::path root_, file_;
  std::map<std::string, Entry> entries_;
  std::set<std::string> changed_;  // keys to write
};

}  // namespace texproc::cli
