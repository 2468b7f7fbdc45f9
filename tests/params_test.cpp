// The parameter table (shaders/common/params.def) against what is made from it or copies it:
// Params' run order, the defaults, the names a profile takes, docs/params.md's list and the list
// scripts/sensitivity.sh sweeps.
#include "reference_cpu/params.h"

#include <gtest/gtest.h>

#include <cstring>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

#include "reference_cpu/pipeline.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

// One row of the table, as text and as the field's value at its default.
struct Row {
  const char* stage;
  const char* type;
  const char* name;
  const char* default_text;  // the C++ expression, as written
  const char* unit;
  bool param;  // LPIR_PARAM (a setting), not LPIR_DERIVED
  bool swept;
  const char* meaning;
  float default_value;  // the expression's value (whole numbers exactly: all are below 2^24)
};

const Row kRows[] = {
#define LPIR_PARAM(stage, type, name, default_value, unit, swept, meaning) \
  {#stage, #type, #name, #default_value, unit, true, swept == 1, meaning, float(default_value)},
#define LPIR_DERIVED(stage, type, name, default_value, unit, meaning) \
  {#stage, #type, #name, #default_value, unit, false, false, meaning, float(default_value)},
#include "shaders/common/params.def"
};

// The source tree's root (the profiles' folder's parent).
std::string SourceDir() { return std::string(LPIR_SENSORS_DIR) + "/.."; }

// A default as the docs and the script show it: the literal without its float suffix.
std::string DefaultText(const Row& r) {
  std::string t = r.default_text;
  if (!t.empty() && t.back() == 'f' && t.find_first_not_of("-.0123456789ef") == std::string::npos)
    t.pop_back();
  return t;
}

// `text` fit for a markdown table cell.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// docs/params.md's generated part: the parameters' table, then the fields the profile sets.
std::string DocsList() {
  std::string s =
      "| parameter | stage | type | default | unit | meaning |\n|---|---|---|---|---|---|\n";
  std::string derived;
  for (const Row& r : kRows) {
    if (!r.param) {
      derived += std::string(derived.empty() ? "" : ", ") + "`" + r.name + "`";
      continue;
    }
    s += std::string("| `") + r.name + "` | " + r.stage + " | " + r.type + " | " + DefaultText(r) +
         " | " + Cell(r.unit) + " | " + Cell(r.meaning) + " |\n";
  }
  return s + "\nSet from the sensor profile, not parameters: " + derived + ".\n";
}

TEST(Params, RowsFollowTheStagesRunOrder) {
  int at = 0;
  for (const Row& r : kRows) {
    int stage = at;
    while (stage < kStageCount && std::strcmp(kStageNames[stage], r.stage) != 0) ++stage;
    ASSERT_LT(stage, kStageCount) << r.name << ": stage " << r.stage
                                  << " is no stage, or comes before the previous row's";
    at = stage;
  }
}

TEST(Params, DefaultsAreTheTablesAndTheTailIsZero) {
  const Params p = DefaultParams();
  const unsigned char* bytes = reinterpret_cast<const unsigned char*>(&p);
  size_t i = 0;
  for (const Row& r : kRows) {
    float value;
    if (std::strcmp(r.type, "uint") == 0) {
      uint32_t u;
      std::memcpy(&u, bytes + 4 * i, 4);
      value = float(u);
    } else {
      std::memcpy(&value, bytes + 4 * i, 4);
    }
    EXPECT_EQ(value, r.default_value) << r.name;
    ++i;
  }
  for (size_t b = 4 * i; b < sizeof(Params); ++b) EXPECT_EQ(bytes[b], 0) << "byte " << b;
}

TEST(Params, TheSettingsAreTheParamRows) {
  std::vector<std::string> rows;
  for (const Row& r : kRows)
    if (r.param) rows.push_back(r.name);
  EXPECT_EQ(ParamNames(), rows);
  for (const Row& r : kRows) {
    Params p = DefaultParams();
    EXPECT_EQ(ApplyOverride(p, r.name, 3.0f), r.param) << r.name;
    if (!r.param) continue;
    if (std::strcmp(r.type, "uint") == 0) {
      EXPECT_THROW(ApplyOverride(p, r.name, 2.5f), std::invalid_argument) << r.name;
    } else {
      EXPECT_TRUE(ApplyOverride(p, r.name, 2.5f)) << r.name;
    }
  }
}

TEST(Params, DocsListTheTable) {
  if (test::ReadFileBytes(SourceDir() + "/CMakeLists.txt").empty())
    GTEST_SKIP() << "no source tree at " << SourceDir();
  const std::string docs = test::ReadFileBytes(SourceDir() + "/docs/params.md");
  const std::string begin = "<!-- made from shaders/common/params.def -->\n";
  const std::string end = "<!-- end of the table's list -->";
  const size_t a = docs.find(begin), b = docs.find(end);
  ASSERT_NE(a, std::string::npos) << begin;
  ASSERT_NE(b, std::string::npos) << end;
  const std::string want = DocsList();
  EXPECT_TRUE(docs.substr(a + begin.size(), b - a - begin.size()) == want)
      << "docs/params.md disagrees with the table; its list should read:\n"
      << want;
}

TEST(Params, SensitivitySweepsTheSweptRows) {
  std::string want;
  for (const Row& r : kRows)
    if (r.swept) want += std::string(r.name) + " " + DefaultText(r) + " " + r.type + "\n";
  if (test::ReadFileBytes(SourceDir() + "/CMakeLists.txt").empty())
    GTEST_SKIP() << "no source tree at " << SourceDir();
  std::string out;
  ASSERT_EQ(test::RunCommand(SourceDir() + "/scripts/sensitivity.sh --list", &out), 0) << out;
  EXPECT_EQ(out, want);
}

}  // namespace
}  // namespace lpir
