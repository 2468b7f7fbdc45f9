// The progress of the subcommands that work through many files. On a terminal: one status line
// (bar, count, frames per second, time left, running ground fraction) redrawn in place, with every
// message printed above it through Print. Anywhere else (CI logs, pipes, files): never a '\r' or
// an escape code, a plain line whenever another tenth is done or kLineInterval has passed.
// Nothing when disabled (messages given to Print are still printed).
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace lpir {

class Progress {
 public:
  // Off a terminal, a line at least this often while items get done.
  static constexpr std::chrono::seconds kLineInterval{10};

  // Draws on stderr, as a status line when stderr is a terminal (isatty).
  Progress(size_t total, bool enabled);
  // Draws on `out` (not owned), as a status line when `tty`. For tests.
  Progress(size_t total, bool enabled, std::FILE* out, bool tty);
  ~Progress();  // ends the status line (the cursor leaves it at the start of a fresh line)

  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // One item done: `points` of which `ground` are ground (both 0 for an item that failed).
  void Step(size_t points = 0, size_t ground = 0);
  // Writes `text` (whole lines) to `to`: on a terminal the status line is erased first and
  // redrawn below the text, so that the two never share a line.
  void Print(std::FILE* to, const std::string& text);

 private:
  std::string Status(bool bar) const;
  void DrawBar();
  void PrintLine();

  size_t total_;
  bool enabled_;
  std::FILE* out_;
  bool tty_;
  size_t done_ = 0;
  size_t points_ = 0, ground_ = 0;  // over the items done
  size_t shown_done_ = 0;           // done_ when the last status was written
  bool drawn_ = false;              // the status line is on the screen (tty)
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace lpir
