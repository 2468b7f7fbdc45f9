// A progress bar for the subcommands that work through many files: one line redrawn with '\r' on
// a terminal, a plain line at every 10 % on anything else (CI logs, pipes), nothing when disabled.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace lpir {

class Progress {
 public:
  // Draws on stderr, as a bar when stderr is a terminal (isatty).
  Progress(size_t total, bool enabled);
  // Draws on `out` (not owned), as a bar when `tty`. For tests.
  Progress(size_t total, bool enabled, std::FILE* out, bool tty);
  ~Progress();  // ends the bar's line (the cursor leaves it at the start of a fresh line)

  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // One item done; `name` (a file, a frame) is shown beside the bar.
  void Step(const std::string& name);

 private:
  void DrawBar();
  void PrintLine();

  size_t total_;
  bool enabled_;
  std::FILE* out_;
  bool tty_;
  size_t done_ = 0;
  std::string name_;        // of the last item done
  size_t shown_done_ = 0;   // done_ when the last bar or line was written
  size_t drawn_width_ = 0;  // characters of the bar's last drawing (0: nothing drawn yet)
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace lpir
