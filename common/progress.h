#pragma once
// A progress line on stderr for long jobs: redrawn in place on a terminal,
// printed every 10 % otherwise (CI logs), silent when disabled.
#include <chrono>
#include <string>

namespace depot {

class Progress {
 public:
  Progress(std::string label, size_t total, bool enabled = true);
  // Reports that `done` of `total` items are finished; `detail` is appended.
  void update(size_t done, const std::string& detail = "");
  // Ends the line.
  void finish();
  double elapsed_seconds() const;

 private:
  std::string label_;
  size_t total_;
  bool enabled_;
  bool tty_;
  int last_decile_ = -1;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace depot
