// Runs the texproc binary and captures its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "support/images.h"

namespace texproc::test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `args` is appended to the binary's path as shell words; `cwd`: the folder
// to run in (empty: this process's).
inline RunResult run_texproc(const std::string& args, const std::string& cwd = "") {
  const std::string dir = std::filesystem::temp_directory_path().string();
  static int counter = 0;
  const std::string base = dir + "/texproc_run_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const std::string cmd = (cwd.empty() ? "" : "cd '" + cwd + "' && ") + std::string(TEXPROC_CLI_PATH) + " " + args +
                          " >" + base + ".out 2>" + base + ".err";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

}  // namespace texproc::test
