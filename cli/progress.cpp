#include "progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace texproc::cli {

Progress::Progress(std::string command, std::size_t total, bool enabled)
    : command_(std::move(command)),
      total_(total),
      enabled_(enabled && total > 0),
      start_(std::chrono::steady_clock::now()) {
  if (!enabled_) return;
  ticker_ = std::thread([this] {
    std::unique_lock lock(mutex_);
    while (!closed_) {
      draw_locked();
      wake_.wait_for(lock, std::chrono::milliseconds(250));
    }
  });
}

Progress::~Progress() { close(); }

void Progress::close() {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    closed_ = true;
    if (enabled_) clear_locked();
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void Progress::started(const std::string& file) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  in_flight_.emplace_back(file, 0.0);
}

void Progress::fraction(const std::string& file, double done) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  for (auto& f : in_flight_)
    if (f.first == file) {
      f.second = std::clamp(done, 0.0, 1.0);
      return;
    }
}

void Progress::finished(const std::string& file, const std::function<void()>& print) {
  std::lock_guard lock(mutex_);
  if (enabled_) clear_locked();
  std::cout.flush();
  print();
  std::cout.flush();
  ++done_;
  auto it = std::find_if(in_flight_.begin(), in_flight_.end(), [&](const auto& f) { return f.first == file; });
  if (it != in_flight_.end()) in_flight_.erase(it);
  if (enabled_ && !closed_) draw_locked();
}

void Progress::clear_locked() {
  if (!drawn_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  drawn_ = false;
}

namespace {
std::string clock_text(double seconds) {
  char b[32];
  const long s = long(seconds + 0.5);
  if (s >= 3600) {
    std::snprintf(b, sizeof b, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  } else {
    std::snprintf(b, sizeof b, "%ld:%02ld", s / 60, s % 60);
  }
  return b;
}
}  // namespace

void Progress::draw_locked() {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  double partial = 0.0;  // the files in work, by how far they have got
  for (const auto& f : in_flight_) partial += f.second;
  char head[160];
  std::snprintf(head, sizeof head, "texproc %s [%zu/%zu] %3d%% %s", command_.c_str(), done_, total_,
                int(100.0 * (double(done_) + partial) / double(total_)), clock_text(elapsed).c_str());
  std::string line = head;
  if (done_ > 0 && elapsed > 0) {
    char rate[96];
    const double per_second = double(done_) / elapsed;
    std::snprintf(rate, sizeof rate, ", %.2f files/s, %s left", per_second,
                  clock_text(double(total_ - done_) / per_second).c_str());
    line += rate;
  }
  if (!in_flight_.empty()) {
    line += ", " + in_flight_.front().first;
    if (in_flight_.front().second > 0.0) {
      char percent[16];
      std::snprintf(percent, sizeof percent, " %d%%", int(100.0 * in_flight_.front().second));
      line += percent;
    }
    if (in_flight_.size() > 1) line += " +" + std::to_string(in_flight_.size() - 1);
  }
  int columns = 100;
  winsize ws{};
  if (::ioctl(2, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 10) columns = ws.ws_col;
  if (int(line.size()) >= columns) line = line.substr(0, std::size_t(columns - 4)) + "...";
  std::fputs(("\r\033[K" + line).c_str(), stderr);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace texproc::cli
