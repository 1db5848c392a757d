// Folders for fault tests: a small tmpfs that fills up, and a folder's
// entries as a sorted list.
#pragma once

#include <sys/mount.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/images.h"

namespace texproc::test {

// A tmpfs of `kib` KiB at a fresh folder named after `name`, or dir == ""
// where this process may not mount one (not root, no CAP_SYS_ADMIN).
struct SmallDisk {
  std::string dir;
  explicit SmallDisk(int kib, bool read_only = false, const std::string& name = "smalldisk") {
    const std::string d = temp_dir(name);
    const std::string opts = "size=" + std::to_string(kib) + "k";
    if (::mount("tmpfs", d.c_str(), "tmpfs", read_only ? MS_RDONLY : 0, opts.c_str()) == 0) dir = d;
  }
  ~SmallDisk() {
    if (!dir.empty()) ::umount2(dir.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  // Fills the disk with a file "filler" of `bytes` bytes.
  void fill_to(std::size_t bytes) const {
    std::ofstream filler(dir + "/filler", std::ios::binary);
    filler << std::string(bytes, 'x');
  }
};

inline std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace texproc::test
