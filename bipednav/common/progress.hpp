#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <string_view>

namespace bipednav {

// A one-line progress bar on stderr for long command-line work. It is drawn only when stderr is a
// terminal (a log file gets no carriage-return lines); finish() draws it full: work that ends early
// (a run that reaches its goal before its time limit) is done, not 30 % done.
class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total, bool enabled = true)
      : label_(std::move(label)), total_(total), enabled_(enabled && total > 0 && ::isatty(::fileno(stderr))) {}
  // Without finish() (work abandoned, e.g. by an exception) the bar stays where it was.
  ~ProgressBar() {
    if (enabled_ && last_pct_ >= 0) std::fprintf(stderr, "\n");
  }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void update(std::size_t done) {
    if (!enabled_) return;
    const int pct = static_cast<int>(100.0 * static_cast<double>(std::min(done, total_)) / static_cast<double>(total_));
    if (pct != last_pct_) draw(pct, {});
  }
  // Draws the bar full with an optional note (e.g. the outcome) and ends the line.
  void finish(std::string_view note = {}) {
    if (!enabled_) return;
    draw(100, note);
    std::fprintf(stderr, "\n");
    enabled_ = false;
  }

 private:
  void draw(int pct, std::string_view note) {
    last_pct_ = pct;
    const int filled = pct / 5;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled, "####################", 20 - filled, "", pct);
    // The note is written from its view: no temporary string (GCC 12 at -O3 flags `" " + std::string`
    // with a false -Wrestrict, GCC PR 105329, in some of the files that include this header).
    if (!note.empty()) {
      std::fputc(' ', stderr);
      std::fwrite(note.data(), 1, note.size(), stderr);
    }
    std::fflush(stderr);
  }

  std::string label_;
  std::size_t total_;
  bool enabled_;
  int last_pct_ = -1;
};

}  // namespace bipednav
