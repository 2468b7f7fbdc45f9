// "Did you mean": the nearest known name to a typo, and none for what is no typo.
#include "host/io/suggest.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lpir {
namespace {

TEST(Suggest, TyposFindTheirName) {
  const std::vector<std::string> commands = {"segment", "evaluate", "simulate", "calibrate",
                                             "demo",    "devices",  "bench",    "topics"};
  EXPECT_EQ(ClosestName("segmnet", commands), "segment");  // two letters swapped
  EXPECT_EQ(ClosestName("segemnt", commands), "segment");
  EXPECT_EQ(ClosestName("evalute", commands), "evaluate");    // one left out
  EXPECT_EQ(ClosestName("simulatee", commands), "simulate");  // one added
  EXPECT_EQ(ClosestName("SEGMENT", commands), "segment");     // case
  const std::vector<std::string> sensors = {"hdl32e", "hdl64e", "os1-128", "os1-64", "vlp16"};
  EXPECT_EQ(ClosestName("hdl-64e", sensors), "hdl64e");
  EXPECT_EQ(ClosestName("HDL64E", sensors), "hdl64e");
  EXPECT_EQ(ClosestName("os1_64", sensors), "os1-64");
  EXPECT_EQ(ClosestName("vlp17", sensors), "vlp16");
  EXPECT_EQ(ClosestName("--sensr", {"--out", "--sensor", "--set"}), "--sensor");
}

TEST(Suggest, NothingNearIsNoGuess) {
  const std::vector<std::string> sensors = {"hdl32e", "hdl64e", "os1-128", "os1-64", "vlp16"};
  EXPECT_EQ(ClosestName("velodyne", sensors), "");
  EXPECT_EQ(ClosestName("", sensors), "");
  EXPECT_EQ(ClosestName("x", {"y"}), "y");  // one letter off: at least 1 is always a typo
  EXPECT_EQ(ClosestName("xy", {"ab"}), "");
  EXPECT_EQ(ClosestName("anything", {}), "");
  EXPECT_EQ(DidYouMean("hdl-64e", sensors), " (did you mean hdl64e?)");
  EXPECT_EQ(DidYouMean("velodyne", sensors), "");
}

TEST(Suggest, TheNearestWinsAndTiesGoToTheFirst) {
  EXPECT_EQ(ClosestName("hdl64", {"hdl32e", "hdl64e"}), "hdl64e");
  EXPECT_EQ(ClosestName("abcd", {"abce", "abcf"}), "abce");
  EXPECT_EQ(ClosestName("abcd", {"abxy", "abce"}), "abce");
}

}  // namespace
}  // namespace lpir
