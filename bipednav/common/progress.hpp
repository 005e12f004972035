#pragma once

#include <cstdio>
#include <string>

namespace bipednav {

// A one-line progress bar on stderr for long command-line work (silent when disabled).
class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total, bool enabled = true)
      : label_(std::move(label)), total_(total), enabled_(enabled) {}
  ~ProgressBar() { finish(); }
  void update(std::size_t done) {
    if (!enabled_ || total_ == 0) return;
    const int pct = static_cast<int>(100.0 * static_cast<double>(done) / static_cast<double>(total_));
    if (pct == last_pct_) return;
    last_pct_ = pct;
    const int filled = pct / 5;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled, "####################", 20 - filled, "", pct);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_ && last_pct_ >= 0) std::fprintf(stderr, "\n");
    enabled_ = false;
  }

 private:
  std::string label_;
  std::size_t total_;
  bool enabled_;
  int last_pct_ = -1;
};

}  // namespace bipednav
