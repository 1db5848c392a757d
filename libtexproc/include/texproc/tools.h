// texproc/tools.h: helpers for programs built on libtexproc the way the
// texproc tool is (atomic output files committed together, batches run in
// order). The tool's own building blocks: they may change in any release,
// outside the API stability promise of docs/library.md.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace texproc {

// What commit() does when the output exists. replace (the default) renames
// over it. keep_identical leaves an old file that holds the same bytes, so
// build systems that check time stamps (Ninja's restat, Make) see no change.
// no_replace never replaces an existing file: commit() fails atomically if
// path() exists at that moment (what the texproc tool does without --force).
enum class CommitPolicy { replace, keep_identical, no_replace };
// Write to temp_path(), then commit() puts it under `path` in one step, so a
// reader (or a build system) never sees a half-written file. If the object is
// destroyed without commit() (an exception, an error), the temporary file is
// gone and `path` is left as it was.
//
// Where the file system allows it (ext4, XFS, Btrfs, tmpfs), the temporary
// is an unnamed file in path()'s folder (O_TMPFILE) that temp_path() names
// as /proc/self/fd/N: a process killed at any moment leaves nothing behind.
// Elsewhere it is a hidden file beside path().
class CommitGroup;

class AtomicFile {
 public:
  // Committed under the policy of the CommitGroup open on this thread, or
  // replace outside any group.
  explicit AtomicFile(std::string path);
  // The same, committed under `policy` whatever the group's policy is.
  AtomicFile(std::string path, CommitPolicy policy);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // A path that writers may open (and truncate) by name: on the same file
  // system as path(). A named temporary is hidden and ends in path()'s
  // extension; its name is cut to fit the folder's name limit.
  const std::string& temp_path() const { return temp_; }
  // Puts the file under path(). Under CommitPolicy::keep_identical, when
  // path() already holds exactly these bytes, drops the temporary instead and
  // leaves path() untouched (its time stamp too); under no_replace an
  // existing path() (even one created since the caller checked) is an error
  // and is left as it was. Returns whether path() was written. Throws
  // Error{io} on failure, naming path() and the OS error.
  // While a CommitGroup is open on the calling thread, the file is handed to
  // the group instead, to be put in place with the group's other files
  // (returns true).
  bool commit();

 private:
  friend class CommitGroup;
  AtomicFile() = default;
  bool commit_now();
  void check_free() const;  // under no_replace: Error{io} if path() exists now
  std::string path_, temp_;
  int fd_ = -1;      // the unnamed temporary, or -1 for a named one
  int policy_ = -1;  // a CommitPolicy of its own, or -1 for the group's (replace outside a group)
  bool committed_ = false;
};

// The outputs of one piece of work, put in place together or not at all:
// while a group is open on a thread, every AtomicFile committed on that
// thread waits in the group. commit() then checks that each can be put in
// place (no_replace: none has appeared) and renames them in the order they
// were written; a group destroyed without commit() (an exception, a failure
// after the first output) discards them all, so a build system never sees
// half of a job's outputs. A group opened while another is open on the
// same thread collects its own files until it is closed. Files without a
// policy of their own are committed under the group's `policy`.
class CommitGroup {
 public:
  explicit CommitGroup(CommitPolicy policy = CommitPolicy::replace);
  ~CommitGroup();
  CommitGroup(const CommitGroup&) = delete;
  CommitGroup& operator=(const CommitGroup&) = delete;
  // Throws Error{io}; a file already put in place when a later one fails
  // is removed again if it was new.
  void commit();

 private:
  friend class AtomicFile;
  std::vector<std::unique_ptr<AtomicFile>> files_;
  CommitGroup* outer_ = nullptr;
  CommitPolicy policy_ = CommitPolicy::replace;
};

// Removes every named temporary this process has open (hidden files beside
// outputs; unnamed ones vanish with the process by themselves). Thread-safe;
// for a signal-handling thread before the process exits.
void remove_pending_temporaries();

// Removes the hidden temporaries (".~NAME.tmpPID-N.EXT") that processes no
// longer running left in `folder` (killed with SIGKILL, or a power loss).
// Done once a folder by the first AtomicFile made there; returns how many.
int remove_stale_temporaries(const std::string& folder);

// The files a process using libtexproc needs beside the system's
// libraries: first the executable or shared library that holds libtexproc,
// then each runtime module (OpenEXR, OpenImageIO, OpenColorIO) found where
// it would be loaded from (absent ones are left out). Canonical paths.
// What a remote-execution action ships with the tool, and what a cache key
// for the tool hashes.
std::vector<std::string> runtime_files();

// The libraries texproc uses and their versions ({"libtiff", "4.5.0"},
// ...): the ones linked as the running process reports them, the runtime
// modules' (OpenEXR, OpenImageIO, OpenColorIO) and astc-encoder's as built
// against. For cache keys and bug reports.
std::vector<std::pair<std::string, std::string>> linked_libraries();

// Writes `bytes` to `path` atomically (an AtomicFile: the group's policy, or
// `policy`). Throws Error{io}.
void write_file_atomic(const std::string& path, const std::string& bytes);
void write_file_atomic(const std::string& path, const std::string& bytes, CommitPolicy policy);

// A batch of `count` items, `in_flight` at most at a time: work(i) runs in
// parallel for i = 0, 1, ... (started in order of i), and done(i) runs for
// each item one at a time in order of i, once it and every item before it
// have finished work. done returning false stops the batch: no item starts
// after that (those in flight finish and get done). Returns how many items
// were started (the rest were not run).
std::size_t for_each_in_order(std::size_t count, std::size_t in_flight, const std::function<void(std::size_t)>& work,
                              const std::function<bool(std::size_t)>& done);

}  // namespace texproc
