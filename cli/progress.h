// A one-line progress display on stderr for batches: files done, the file
// in work, throughput and time left, redrawn a few times a second. Drawn
// only when enabled (stderr is a terminal, or --progress); otherwise every
// call but `finished`'s print is a no-op.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace texproc::cli {

class Progress {
 public:
  Progress(std::string command, std::size_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void started(const std::string& file);
  // How far the work on `file` (started, not finished) has got, in [0, 1]:
  // counted into the total and shown beside the file's name.
  void fraction(const std::string& file, double done);
  // Clears the progress line, runs `print` (which writes whole lines to
  // stdout or stderr), counts `file` done and redraws.
  void finished(const std::string& file, const std::function<void()>& print);
  // Stops the redrawing and erases the line.
  void close();

 private:
  void draw_locked();
  void clear_locked();

  std::string command_;
  std::size_t total_, done_ = 0;
  bool enabled_;
  bool closed_ = false;
  bool drawn_ = false;
  std::vector<std::pair<std::string, double>> in_flight_;  // file, fraction done
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread ticker_;
};

}  // namespace texproc::cli
