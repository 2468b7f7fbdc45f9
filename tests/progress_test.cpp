// Tests of the command-line progress: plain lines without '\r' or escape codes off a terminal, a
// status line redrawn in place on one with messages printed above it, nothing when disabled.
#include "apps/cli/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace lpir {
namespace {

// Runs `steps` steps of a bar over `total` into a temporary file and returns what was written.
// Each step is a frame of 100 points, 25 of them ground; with `message`, Print writes a line to
// the same file after every step.
std::string Capture(size_t total, size_t steps, bool enabled, bool tty, bool message = false) {
  std::FILE* file = std::tmpfile();
  EXPECT_NE(file, nullptr);
  {
    Progress progress(total, enabled, file, tty);
    for (size_t i = 0; i < steps; ++i) {
      progress.Step(100, 25);
      if (message) progress.Print(file, "message " + std::to_string(i) + "\n");
    }
  }
  std::rewind(file);
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), file)) > 0) text.append(buf, n);
  std::fclose(file);
  return text;
}

size_t CountOf(const std::string& text, char c) {
  size_t count = 0;
  for (char t : text) count += t == c;
  return count;
}

TEST(Progress, OffATerminalPrintsAPlainLineEveryTenth) {
  std::string text = Capture(100, 100, true, false);
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_EQ(CountOf(text, '\n'), 10u) << text;
  EXPECT_EQ(text.rfind("progress: ", 0), 0u) << text;
  EXPECT_NE(text.find("10/100  10%"), std::string::npos) << text;
  EXPECT_NE(text.find("100/100 100%"), std::string::npos) << text;
  EXPECT_NE(text.find("25.0% ground  "), std::string::npos) << text;
  EXPECT_EQ(text.find('\x1b'), std::string::npos) << text;
}

TEST(Progress, OffATerminalSaysWhereAnEarlyStopEnded) {
  std::string text = Capture(100, 15, true, false);
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_EQ(CountOf(text, '\n'), 2u) << text;  // at 10, then 15 from the destructor
  EXPECT_NE(text.find("15/100  15%"), std::string::npos) << text;
}

TEST(Progress, OnATerminalRedrawsOneLine) {
  std::string text = Capture(3, 3, true, true);
  EXPECT_EQ(text.front(), '\r') << text;
  EXPECT_EQ(CountOf(text, '\n'), 1u) << text;
  EXPECT_EQ(text.back(), '\n') << text;
  EXPECT_NE(text.find("3/3 100%"), std::string::npos) << text;
  EXPECT_NE(text.find("[####################]"), std::string::npos) << text;
}

TEST(Progress, OnATerminalTheLineNeverWraps) {
  // A file is no terminal: the bar assumes 80 columns.
  std::string text = Capture(5, 5, true, true);
  size_t start = 0;
  while ((start = text.find("\r\x1b[K", start)) != std::string::npos) {
    size_t end = text.find_first_of("\r\n", start + 1);
    EXPECT_LT(end - start - 4, 80u) << text.substr(start + 4, end - start - 4);
    start = end;
  }
  EXPECT_NE(text.find("25.0% ground"), std::string::npos) << text;
  EXPECT_NE(text.find("frames/s"), std::string::npos) << text;
}

TEST(Progress, OnATerminalMessagesPrintAboveTheErasedBar) {
  std::string text = Capture(3, 3, true, true, /*message=*/true);
  // Every message starts on a line the bar was erased from, and the bar is redrawn after it.
  for (int i = 0; i < 3; ++i) {
    std::string m = "\r\x1b[Kmessage " + std::to_string(i) + "\n\r\x1b[K[";
    EXPECT_NE(text.find(m), std::string::npos) << i << "\n" << text;
  }
}

TEST(Progress, OffATerminalMessagesAreLinesOfTheirOwn) {
  std::string text = Capture(3, 3, true, false, /*message=*/true);
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_NE(text.find("\nmessage 1\nprogress: "), std::string::npos) << text;
}

TEST(Progress, DisabledWritesNothing) {
  EXPECT_EQ(Capture(10, 10, false, false), "");
  EXPECT_EQ(Capture(10, 10, false, true), "");
  EXPECT_EQ(Capture(10, 0, true, true), "");
}

TEST(Progress, StderrThatIsNoTerminalGetsNoCarriageReturn) {
  testing::internal::CaptureStderr();  // stderr becomes a file, whatever runs the test
  {
    Progress progress(4, true);
    for (int i = 0; i < 4; ++i) progress.Step(10, 1);
  }
  std::string text = testing::internal::GetCapturedStderr();
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_NE(text.find("4/4 100%"), std::string::npos) << text;
}

}  // namespace
}  // namespace lpir
