// The progress bar of the subcommands (see progress.h).
#include "apps/cli/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace lpir {
namespace {

constexpr size_t kBarCells = 30;
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);

// Columns of the terminal behind `out`; 80 when unknown.
size_t TerminalColumns(std::FILE* out) {
  winsize size{};
  if (::ioctl(::fileno(out), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

std::string FormatDuration(double seconds) {
  long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld", s / 60, s % 60);
  }
  return buf;
}

// "123/456  27%": the count and, when the total is known, the percentage.
std::string Count(size_t done, size_t total) {
  char buf[64];
  if (total == 0) {
    std::snprintf(buf, sizeof(buf), "%zu", done);
  } else {
    int width = std::snprintf(nullptr, 0, "%zu", total);  // counts keep their place
    std::snprintf(buf, sizeof(buf), "%*zu/%zu %3zu%%", width, done, total,
                  std::min<size_t>(100, done * 100 / total));
  }
  return buf;
}

}  // namespace

Progress::Progress(size_t total, bool enabled)
    : Progress(total, enabled, stderr, ::isatty(::fileno(stderr)) == 1) {}

Progress::Progress(size_t total, bool enabled, std::FILE* out, bool tty)
    : total_(total),
      enabled_(enabled && out != nullptr),
      out_(out),
      tty_(tty),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() {
  if (!enabled_ || done_ == 0) return;
  if (tty_) {
    if (shown_done_ != done_) DrawBar();  // the last step fell between redraws
    std::fputc('\n', out_);
    std::fflush(out_);
  } else if (shown_done_ != done_) {
    PrintLine();  // where it ended, also when it stopped early
  }
}

void Progress::Step(const std::string& name) {
  if (!enabled_) return;
  ++done_;
  name_ = name;
  if (tty_) {
    // Redraw at most every kRedrawInterval, but always the first and the last step.
    auto now = std::chrono::steady_clock::now();
    bool last = total_ != 0 && done_ == total_;
    if (drawn_width_ == 0 || last || now - last_draw_ >= kRedrawInterval) DrawBar();
  } else {
    // A line whenever another tenth of the total is done (every step when the total is unknown
    // would flood a log, so then only the destructor's last line).
    if (total_ != 0 && (done_ * 10 / total_ > shown_done_ * 10 / total_ || done_ == total_)) {
      PrintLine();
    }
  }
}

void Progress::DrawBar() {
  auto now = std::chrono::steady_clock::now();
  last_draw_ = now;
  shown_done_ = done_;
  double elapsed = std::chrono::duration<double>(now - start_).count();

  std::string line;
  if (total_ != 0) {
    size_t filled = std::min(kBarCells, done_ * kBarCells / total_);
    line = "[" + std::string(filled, '#') + std::string(kBarCells - filled, '.') + "] ";
  }
  line += Count(done_, total_) + "  " + FormatDuration(elapsed);
  if (total_ != 0 && done_ < total_) {
    line += " (" + FormatDuration(elapsed / done_ * (total_ - done_)) + " left)";
  }
  // The name, shortened from the front so that the line never wraps (a wrapped line cannot be
  // redrawn with '\r').
  size_t columns = TerminalColumns(out_);
  if (!name_.empty() && line.size() + 6 < columns) {
    size_t room = columns - 1 - line.size() - 2;
    std::string name = name_.size() <= room ? name_ : "..." + name_.substr(name_.size() - room + 3);
    line += "  " + name;
  }
  if (line.size() >= columns) line.resize(columns - 1);

  std::string text = "\r" + line;
  if (line.size() < drawn_width_) text += std::string(drawn_width_ - line.size(), ' ');
  drawn_width_ = line.size();
  std::fputs(text.c_str(), out_);
  std::fflush(out_);
}

void Progress::PrintLine() {
  shown_done_ = done_;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line = "progress: " + Count(done_, total_) + "  " + FormatDuration(elapsed);
  if (!name_.empty()) line += "  " + name_;
  line += "\n";
  std::fputs(line.c_str(), out_);
  std::fflush(out_);
}

}  // namespace lpir
