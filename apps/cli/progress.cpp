// The progress of the subcommands (see progress.h).
#include "apps/cli/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace lpir {
namespace {

constexpr size_t kBarCells = 20;
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
// Carriage return, then erase to the end of the line (ANSI EL 0).
constexpr char kEraseLine[] = "\r\x1b[K";

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
    if (shown_done_ != done_ || !drawn_) DrawBar();  // the last step fell between redraws
    std::fputc('\n', out_);
    std::fflush(out_);
  } else if (shown_done_ != done_) {
    PrintLine();  // where it ended, also when it stopped early
  }
}

void Progress::Step(size_t points, size_t ground) {
  if (!enabled_) return;
  ++done_;
  points_ += points;
  ground_ += ground;
  auto now = std::chrono::steady_clock::now();
  if (tty_) {
    // Redraw at most every kRedrawInterval, but always the first and the last step.
    bool last = total_ != 0 && done_ == total_;
    if (!drawn_ || last || now - last_draw_ >= kRedrawInterval) DrawBar();
  } else {
    // A line whenever another tenth of the total is done, or kLineInterval after the last one.
    bool tenth =
        total_ != 0 && (done_ * 10 / total_ > shown_done_ * 10 / total_ || done_ == total_);
    if (tenth || now - last_draw_ >= kLineInterval) PrintLine();
  }
}

void Progress::Print(std::FILE* to, const std::string& text) {
  if (enabled_ && tty_ && drawn_) {
    std::fputs(kEraseLine, out_);
    std::fflush(out_);
    drawn_ = false;
  }
  std::fputs(text.c_str(), to);
  std::fflush(to);
  if (enabled_ && tty_ && done_ > 0) DrawBar();
}

std::string Progress::Status(bool bar) const {
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line;
  if (bar && total_ != 0) {
    size_t filled = std::min(kBarCells, done_ * kBarCells / total_);
    line = "[" + std::string(filled, '#') + std::string(kBarCells - filled, '.') + "] ";
  }
  line += Count(done_, total_);
  char buf[96];
  if (points_ != 0) {
    std::snprintf(buf, sizeof(buf), "  %.1f%% ground", 100.0 * double(ground_) / double(points_));
    line += buf;
  }
  if (elapsed > 0) {
    const double rate = double(done_) / elapsed;
    std::snprintf(buf, sizeof(buf), rate < 100 ? "  %.1f frames/s" : "  %.0f frames/s", rate);
    line += buf;
  }
  line += "  " + FormatDuration(elapsed);
  if (total_ != 0 && done_ < total_) {
    line += " (" + FormatDuration(elapsed / double(done_) * double(total_ - done_)) + " left)";
  }
  return line;
}

void Progress::DrawBar() {
  last_draw_ = std::chrono::steady_clock::now();
  shown_done_ = done_;
  std::string line = Status(true);
  // Never wider than the terminal: a wrapped line cannot be redrawn in place.
  size_t columns = TerminalColumns(out_);
  if (line.size() >= columns) line.resize(columns - 1);
  std::fputs((kEraseLine + line).c_str(), out_);
  std::fflush(out_);
  drawn_ = true;
}

void Progress::PrintLine() {
  last_draw_ = std::chrono::steady_clock::now();
  shown_done_ = done_;
  std::fputs(("progress: " + Status(false) + "\n").c_str(), out_);
  std::fflush(out_);
}

}  // namespace lpir
