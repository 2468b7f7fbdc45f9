// LZF decompression (host/io/lzf.h) on hand-assembled streams: each kind of instruction, a
// reference that repeats its own output, the longest length and distance, and every way a stream
// can lie (cut short, reaching before the output, writing past it, ending early).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "host/io/lzf.h"
#include "tests/io_test_helpers.h"

namespace lpir {
namespace {

using test::ThrowsIoError;

const std::string kPath = "stream.pcd";

std::string Decode(const std::vector<uint8_t>& stream, size_t out_size) {
  std::string out(out_size, '?');
  LzfDecompress(kPath, stream.data(), stream.size(), reinterpret_cast<uint8_t*>(out.data()),
                out_size);
  return out;
}

// A literal run of `text` (at most 32 bytes): control byte size - 1, then the bytes.
std::vector<uint8_t> Literal(const std::string& text) {
  std::vector<uint8_t> run(text.size() + 1);
  run[0] = uint8_t(text.size() - 1);
  std::copy(text.begin(), text.end(), run.begin() + 1);
  return run;
}

// A back reference copying `length` (>= 3) bytes from `distance` (1..8192) bytes back.
std::vector<uint8_t> Reference(size_t length, size_t distance) {
  const size_t l = length - 2, d = distance - 1;
  if (l < 7) return {uint8_t(l << 5 | d >> 8), uint8_t(d & 0xff)};
  return {uint8_t(7 << 5 | d >> 8), uint8_t(l - 7), uint8_t(d & 0xff)};
}

std::vector<uint8_t> Join(std::initializer_list<std::vector<uint8_t>> parts) {
  std::vector<uint8_t> out;
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

TEST(IoLzf, LiteralRuns) {
  EXPECT_EQ(Decode(Literal("a"), 1), "a");
  const std::string longest(32, 'z');
  EXPECT_EQ(Decode(Join({Literal(longest), Literal("bc")}), 34), longest + "bc");
  EXPECT_EQ(Decode({}, 0), "");
}

TEST(IoLzf, ShortAndLongReferences) {
  EXPECT_EQ(Decode(Join({Literal("abcdef"), Reference(3, 6)}), 9), "abcdefabc");
  EXPECT_EQ(Decode(Join({Literal("abcdef"), Reference(8, 6)}), 14), "abcdefabcdefab");
  // The longest: 7 + 255 + 2 bytes from a 3-byte instruction.
  const std::string out = Decode(Join({Literal("x"), Reference(264, 1)}), 265);
  EXPECT_EQ(out, std::string(265, 'x'));
}

TEST(IoLzf, AReferenceRepeatsWhatItIsWriting) {
  // distance 2, length 7: "ab" then "ababab" + "a", read while written.
  EXPECT_EQ(Decode(Join({Literal("ab"), Reference(7, 2)}), 9), "ababababa");
}

TEST(IoLzf, TheFarthestReference) {
  std::string text;
  std::vector<uint8_t> stream;
  for (int run = 0; run < 256; ++run) {  // 8192 bytes
    std::string part(32, char('A' + run % 26));
    part[0] = char(run);
    text += part;
    const std::vector<uint8_t> literal = Literal(part);
    stream.insert(stream.end(), literal.begin(), literal.end());
  }
  const std::vector<uint8_t> back = Reference(5, 8192);
  stream.insert(stream.end(), back.begin(), back.end());
  EXPECT_EQ(Decode(stream, 8197), text + text.substr(0, 5));
}

TEST(IoLzf, ALiteralRunCutShort) {
  std::vector<uint8_t> stream = Literal("abcd");
  stream.pop_back();
  EXPECT_TRUE(ThrowsIoError([&] { Decode(stream, 4); }, kPath,
                            {"byte 0 of 4", "a run of 4 bytes cut short"}));
}

TEST(IoLzf, AReferenceCutShort) {
  std::vector<uint8_t> stream = Join({Literal("abc"), Reference(3, 3)});
  stream.pop_back();  // no distance byte
  EXPECT_TRUE(
      ThrowsIoError([&] { Decode(stream, 6); }, kPath, {"byte 4 of 5", "a reference cut short"}));
  std::vector<uint8_t> long_form = Join({Literal("abc"), Reference(20, 3)});
  long_form.resize(5);  // the control byte alone, no length byte
  EXPECT_TRUE(ThrowsIoError([&] { Decode(long_form, 23); }, kPath, {"a reference cut short"}));
}

TEST(IoLzf, AReferenceBeforeTheStart) {
  EXPECT_TRUE(ThrowsIoError(
      [&] {
        Decode(Join({Literal("abc"), Reference(3, 4)}), 6);
      },
      kPath, {"byte 4", "4 bytes back from output byte 3", "before the start of the output"}));
  EXPECT_TRUE(ThrowsIoError([&] { Decode(Reference(3, 1), 3); }, kPath, {"byte 0"}));
}

TEST(IoLzf, MoreOutputThanExpected) {
  EXPECT_TRUE(ThrowsIoError([&] { Decode(Literal("abcd"), 3); }, kPath,
                            {"copies 4 bytes at output byte 0", "past the 3 bytes"}));
  EXPECT_TRUE(ThrowsIoError(
      [&] {
        Decode(Join({Literal("ab"), Reference(9, 2)}), 10);
      },
      kPath, {"copies 9 bytes at output byte 2", "past the 10 bytes"}));
}

TEST(IoLzf, LessOutputThanExpected) {
  EXPECT_TRUE(
      ThrowsIoError([&] { Decode(Literal("abc"), 4); }, kPath, {"decodes to 3 bytes, not the 4"}));
}

TEST(IoLzf, TheExpansionBoundHolds) {
  // The densest stream, 3-byte references of 264 bytes each, decodes to 88 times its size.
  std::vector<uint8_t> stream = Literal("abc");
  size_t out = 3;
  while (stream.size() < 3000) {
    const std::vector<uint8_t> back = Reference(264, 1);
    stream.insert(stream.end(), back.begin(), back.end());
    out += 264;
  }
  EXPECT_EQ(Decode(stream, out).size(), out);
  EXPECT_LE(out, stream.size() * kLzfMaxExpansion);
  EXPECT_GT(out, (stream.size() - 4) * (kLzfMaxExpansion - 1));  // and the bound is tight
}

}  // namespace
}  // namespace lpir
