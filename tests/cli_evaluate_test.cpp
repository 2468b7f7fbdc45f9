// lpir-gseg evaluate, run as a process on small label files written here: the JSON values of every
// protocol, folder and file arguments, the table, the per-class and per-range breakdowns, the
// RELLIS-3D ontology, and the error exits; on the real RELLIS-3D scan, segment's F1.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "host/eval/metrics.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;

// --- a minimal JSON reader: enough to check that the output is exactly one object -------------

struct Json {
  enum Kind { kNull, kNumber, kString, kArray, kObject } kind = kNull;
  double number = 0;
  std::string text;
  std::vector<Json> items;
  std::map<std::string, Json> fields;
  std::vector<std::string> order;  // field names as they came

  const Json& operator[](const std::string& key) const {
    static const Json missing;
    auto it = fields.find(key);
    return it == fields.end() ? missing : it->second;
  }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& s) : s_(s) {}
  // Parses the whole string as one value; false on any syntax error or trailing text.
  bool ReadAll(Json* out) {
    if (!Value(out)) return false;
    Space();
    return i_ == s_.size();
  }

 private:
  void Space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\t')) ++i_;
  }
  bool Value(Json* v) {
    Space();
    if (i_ >= s_.size()) return false;
    char c = s_[i_];
    if (c == '{') return Object(v);
    if (c == '[') return Array(v);
    if (c == '"') {
      v->kind = Json::kString;
      return String(&v->text);
    }
    char* end = nullptr;
    v->kind = Json::kNumber;
    v->number = std::strtod(s_.c_str() + i_, &end);
    if (end == s_.c_str() + i_) return false;
    i_ = end - s_.c_str();
    return true;
  }
  bool String(std::string* out) {
    if (s_[i_++] != '"') return false;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') ++i_;
      *out += s_[i_++];
    }
    return i_++ < s_.size();
  }
  bool Array(Json* v) {
    v->kind = Json::kArray;
    ++i_;
    Space();
    if (i_ < s_.size() && s_[i_] == ']') return ++i_, true;
    while (true) {
      v->items.emplace_back();
      if (!Value(&v->items.back())) return false;
      Space();
      if (i_ >= s_.size()) return false;
      if (s_[i_] == ']') return ++i_, true;
      if (s_[i_++] != ',') return false;
    }
  }
  bool Object(Json* v) {
    v->kind = Json::kObject;
    ++i_;
    Space();
    if (i_ < s_.size() && s_[i_] == '}') return ++i_, true;
    while (true) {
      Space();
      std::string key;
      if (i_ >= s_.size() || !String(&key)) return false;
      Space();
      if (i_ >= s_.size() || s_[i_++] != ':') return false;
      if (v->fields.count(key)) return false;  // duplicate key
      v->order.push_back(key);
      if (!Value(&v->fields[key])) return false;
      Space();
      if (i_ >= s_.size()) return false;
      if (s_[i_] == '}') return ++i_, true;
      if (s_[i_++] != ',') return false;
    }
  }
  const std::string& s_;
  size_t i_ = 0;
};

// --- fixtures --------------------------------------------------------------------------------

void WriteU32(const std::string& path, const std::vector<uint32_t>& v) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * 4));
}

void WriteScan(const std::string& path, const std::vector<float>& z) {
  std::vector<float> xyzi;
  for (size_t i = 0; i < z.size(); ++i) xyzi.insert(xyzi.end(), {5.0f + i, 1.0f, z[i], 0.5f});
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(xyzi.data()), std::streamsize(xyzi.size() * 4));
}

// A scan of the given points (x, y, z each), intensity 0.5.
void WriteXyz(const std::string& path, const std::vector<std::array<float, 3>>& points) {
  std::vector<float> xyzi;
  for (const auto& p : points) xyzi.insert(xyzi.end(), {p[0], p[1], p[2], 0.5f});
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(xyzi.data()), std::streamsize(xyzi.size() * 4));
}

// Frame "a": the hand-counted frame of eval_metrics_test (DG TP 3 FP 5 FN 2 TN 4; PP/GG TP 3
// FP 1 FN 2 TN 2; PW TP 4 FP 3 FN 3 TN 3 with one predicted unlabeled point left out).
const std::vector<uint32_t> kGtA = {40, 40, 72, 48, 10, 10, 70, 70, 70, 0, 1, 50, 40 | (5u << 16),
                                    70};
const std::vector<uint32_t> kPredA = {1, 0, 1, 0, 1, 0, 1, 0, 1, 1, 0, 0, 1, 1};
const std::vector<float> kZA = {-1.7f, -1.7f, -1.6f, -1.8f, -1.0f, -0.5f, -1.5f,
                                -1.5f, -0.5f, -1.7f, -3.0f, 2.0f,  -1.7f, -1.2975f};
// Frame "b": TP 2, FP 1, TN 1 under every protocol.
const std::vector<uint32_t> kGtB = {40, 40, 10, 10};
const std::vector<uint32_t> kPredB = {1, 1, 0, 1};
const std::vector<float> kZB = {-1.7f, -1.7f, -1.0f, -1.0f};

class CliEvaluate : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::TempDir();
    fs::create_directories(root_ + "/seq/labels");
    fs::create_directories(root_ + "/seq/velodyne");
    fs::create_directories(root_ + "/pred");
    WriteU32(root_ + "/seq/labels/a.label", kGtA);
    WriteU32(root_ + "/seq/labels/b.label", kGtB);
    WriteScan(root_ + "/seq/velodyne/a.bin", kZA);
    WriteScan(root_ + "/seq/velodyne/b.bin", kZB);
    WriteU32(root_ + "/pred/a.label", kPredA);
    WriteU32(root_ + "/pred/b.label", kPredB);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }

  // Runs `lpir-gseg evaluate ARGS`; returns the exit code, output in *out.
  int Evaluate(const std::string& args, std::string* out) {
    return test::RunCommand("'" + test::CliPath() + "' evaluate " + args, out);
  }

  Json EvaluateJson(const std::string& args) {
    std::string out;
    EXPECT_EQ(Evaluate(args + " --json", &out), 0) << out;
    Json j;
    EXPECT_TRUE(JsonReader(out).ReadAll(&j)) << "not exactly one JSON value:\n" << out;
    EXPECT_EQ(j.kind, Json::kObject) << out;
    return j;
  }

  std::string root_;
};

void ExpectScores(const Json& j, double p, double r, double f1, double iou) {
  ASSERT_EQ(j.kind, Json::kObject);
  EXPECT_EQ(j.order, (std::vector<std::string>{"precision", "recall", "f1", "iou"}));
  EXPECT_DOUBLE_EQ(j["precision"].number, p);
  EXPECT_DOUBLE_EQ(j["recall"].number, r);
  EXPECT_DOUBLE_EQ(j["f1"].number, f1);
  EXPECT_DOUBLE_EQ(j["iou"].number, iou);
}

double F1(double p, double r) { return 2 * p * r / (p + r); }

TEST_F(CliEvaluate, JsonHoldsEveryProtocolPerFrameAndInTotal) {
  Json j = EvaluateJson("--pred " + root_ + "/pred --gt " + root_ + "/seq/labels --protocol all");
  EXPECT_EQ(j.order, (std::vector<std::string>{"frames", "total"}));
  const Json& frames = j["frames"];
  ASSERT_EQ(frames.kind, Json::kArray);
  ASSERT_EQ(frames.items.size(), 2u);
  const Json& a = frames.items[0];
  const Json& b = frames.items[1];
  EXPECT_EQ(a["name"].text, "a");
  EXPECT_EQ(b["name"].text, "b");
  EXPECT_EQ(a.order, (std::vector<std::string>{"name", "dg", "pp", "pw", "gg"}));
  ExpectScores(a["dg"], 3.0 / 8, 3.0 / 5, 6.0 / 13, 3.0 / 10);
  ExpectScores(a["pp"], 3.0 / 4, 3.0 / 5, 2.0 / 3, 3.0 / 6);
  ExpectScores(a["pw"], 4.0 / 7, 4.0 / 7, 4.0 / 7, 4.0 / 10);
  ExpectScores(a["gg"], 3.0 / 4, 3.0 / 5, 2.0 / 3, 3.0 / 6);
  for (const char* p : {"dg", "pp", "pw", "gg"}) ExpectScores(b[p], 2.0 / 3, 1.0, 0.8, 2.0 / 3);
  const Json& total = j["total"];
  EXPECT_EQ(total.order, (std::vector<std::string>{"dg", "pp", "pw", "gg"}));
  // DG sums TP 5, FP 6, FN 2; GG sums TP 5, FP 2, FN 2; PP and PW average the frames.
  ExpectScores(total["dg"], 5.0 / 11, 5.0 / 7, F1(5.0 / 11, 5.0 / 7), 5.0 / 13);
  ExpectScores(total["gg"], 5.0 / 7, 5.0 / 7, F1(5.0 / 7, 5.0 / 7), 5.0 / 9);
  ExpectScores(total["pp"], (3.0 / 4 + 2.0 / 3) / 2, (3.0 / 5 + 1.0) / 2, (2.0 / 3 + 0.8) / 2,
               (3.0 / 6 + 2.0 / 3) / 2);
  ExpectScores(total["pw"], (4.0 / 7 + 2.0 / 3) / 2, (4.0 / 7 + 1.0) / 2, (4.0 / 7 + 0.8) / 2,
               (4.0 / 10 + 2.0 / 3) / 2);
}

TEST_F(CliEvaluate, OnlyTheRequestedProtocolsAndFilesOrFolders) {
  // Two --gt values (a file and a file), one protocol.
  Json j = EvaluateJson("--pred " + root_ + "/pred --gt " + root_ + "/seq/labels/b.label " + root_ +
                        "/seq/labels/a.label --protocol gg");
  ASSERT_EQ(j["frames"].items.size(), 2u);
  EXPECT_EQ(j["frames"].items[0]["name"].text, "b");  // in the order given
  EXPECT_EQ(j["frames"].items[0].order, (std::vector<std::string>{"name", "gg"}));
  EXPECT_EQ(j["total"].order, std::vector<std::string>{"gg"});
  // A comma-separated list; the same file named twice (alone and through its folder) counts once.
  Json k = EvaluateJson("--protocol pw,dg --gt " + root_ + "/seq/labels/a.label " + root_ +
                        "/seq/labels --pred " + root_ + "/pred");
  ASSERT_EQ(k["frames"].items.size(), 2u);
  EXPECT_EQ(k["total"].order, (std::vector<std::string>{"pw", "dg"}));
}

TEST_F(CliEvaluate, PwFindsHeightsInScansFolder) {
  // Ground truth outside a labels/ folder: pw needs --scans.
  fs::create_directories(root_ + "/flat");
  fs::copy_file(root_ + "/seq/labels/a.label", root_ + "/flat/a.label");
  std::string out;
  EXPECT_NE(Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/flat --protocol pw", &out), 0);
  EXPECT_NE(out.find("needs each point's z"), std::string::npos) << out;
  EXPECT_NE(out.find("--scans"), std::string::npos) << out;
  // DG does not.
  EXPECT_EQ(Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/flat --protocol dg", &out), 0)
      << out;
  Json j = EvaluateJson("--pred " + root_ + "/pred --gt " + root_ + "/flat --protocol pw --scans " +
                        root_ + "/seq/velodyne");
  ExpectScores(j["total"]["pw"], 4.0 / 7, 4.0 / 7, 4.0 / 7, 4.0 / 10);
}

TEST_F(CliEvaluate, HumanTable) {
  std::string out;
  ASSERT_EQ(
      Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/seq/labels --protocol dg,pp", &out), 0)
      << out;
  EXPECT_NE(out.find("DG (DipG-Seg)"), std::string::npos) << out;
  EXPECT_NE(out.find("PP (Patchwork++)"), std::string::npos) << out;
  EXPECT_NE(out.find("a         37.50%     60.00%     46.15%     30.00%"), std::string::npos)
      << out;
  EXPECT_NE(out.find("total     45.45%     71.43%"), std::string::npos) << out;
  EXPECT_NE(out.find("mean      70.83%     80.00%"), std::string::npos) << out;
}

TEST_F(CliEvaluate, Errors) {
  const std::string pred = " --pred " + root_ + "/pred";
  const std::string gt = " --gt " + root_ + "/seq/labels";
  std::string out;
  // No prediction for any ground truth: names both files.
  fs::remove(root_ + "/pred/b.label");
  EXPECT_EQ(Evaluate(pred + " --gt " + root_ + "/seq/labels/b.label", &out), 4);
  EXPECT_NE(out.find("no prediction for ground truth " + root_ + "/seq/labels/b.label"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find(root_ + "/pred/b.label does not exist"), std::string::npos) << out;
  // Count mismatch: names both files and both counts.
  WriteU32(root_ + "/pred/b.label", {1, 1, 0});
  EXPECT_NE(Evaluate(pred + gt + " --protocol dg", &out), 0);
  EXPECT_NE(out.find("prediction " + root_ + "/pred/b.label has 3 labels but ground truth " +
                     root_ + "/seq/labels/b.label has 4"),
            std::string::npos)
      << out;
  // A prediction that is not 0/1 (ground truth passed as prediction, say).
  WriteU32(root_ + "/pred/b.label", {1, 40, 0, 1});
  EXPECT_NE(Evaluate(pred + gt + " --protocol dg", &out), 0);
  EXPECT_NE(out.find("label 1 is 40"), std::string::npos) << out;
  WriteU32(root_ + "/pred/b.label", kPredB);
  // Unknown protocol.
  EXPECT_NE(Evaluate(pred + gt + " --protocol kitti", &out), 0);
  EXPECT_NE(out.find("unknown protocol 'kitti'"), std::string::npos) << out;
  // Missing options and values.
  EXPECT_NE(Evaluate(pred + " --gt --protocol dg", &out), 0);
  EXPECT_NE(out.find("--gt needs at least one"), std::string::npos) << out;
  EXPECT_NE(Evaluate(gt + " --protocol dg", &out), 0);
  EXPECT_NE(out.find("--pred is required"), std::string::npos) << out;
  EXPECT_NE(Evaluate(pred + " --gt " + root_ + "/nothing --protocol dg", &out), 0);
  EXPECT_NE(out.find(root_ + "/nothing"), std::string::npos) << out;
  // Two ground-truth files of one stem cannot share a prediction folder.
  fs::create_directories(root_ + "/other");
  WriteU32(root_ + "/other/a.label", kGtA);
  EXPECT_NE(Evaluate(pred + gt + " " + root_ + "/other --protocol dg", &out), 0);
  EXPECT_NE(out.find("share the stem 'a'"), std::string::npos) << out;
}

TEST_F(CliEvaluate, DefaultsToDgAsPythonDoes) {
  const std::string args = "--pred " + root_ + "/pred --gt " + root_ + "/seq/labels";
  Json plain = EvaluateJson(args);
  EXPECT_EQ(plain["total"].order, std::vector<std::string>{"dg"});
  ExpectScores(plain["total"]["dg"], 5.0 / 11, 5.0 / 7, F1(5.0 / 11, 5.0 / 7), 5.0 / 13);
  // --opt=value and the short form give the same.
  std::string a, b;
  ASSERT_EQ(Evaluate("--pred=" + root_ + "/pred --gt=" + root_ + "/seq/labels -p dg --json", &a), 0)
      << a;
  ASSERT_EQ(Evaluate(args + " --json", &b), 0) << b;
  EXPECT_EQ(a, b);
}

TEST_F(CliEvaluate, MissingPredictionsAreNamedAndTheRestScored) {
  fs::remove(root_ + "/pred/a.label");
  const std::string args = "--pred " + root_ + "/pred --gt " + root_ + "/seq/labels --protocol dg";
  std::string out;
  EXPECT_EQ(Evaluate(args + " --json", &out), 1) << out;
  EXPECT_NE(out.find("1 of 2 predictions missing"), std::string::npos) << out;
  EXPECT_NE(out.find(root_ + "/pred/a.label"), std::string::npos) << out;
  // b alone is scored: TP 2, FP 1, FN 0; the JSON names what is missing.
  const size_t start = out.find('{'), end = out.find("}\n", start);
  ASSERT_NE(start, std::string::npos) << out;
  Json j;
  ASSERT_TRUE(JsonReader(out.substr(start, end + 2 - start)).ReadAll(&j)) << out;
  ASSERT_EQ(j["frames"].items.size(), 1u);
  EXPECT_EQ(j["frames"].items[0]["name"].text, "b");
  ExpectScores(j["total"]["dg"], 2.0 / 3, 1.0, 0.8, 2.0 / 3);
  ASSERT_EQ(j["missing"].items.size(), 1u);
  EXPECT_EQ(j["missing"].items[0].text, root_ + "/pred/a.label");
  // The tables too, with the same exit code.
  EXPECT_EQ(Evaluate(args, &out), 1) << out;
  EXPECT_NE(out.find("DG (DipG-Seg)"), std::string::npos) << out;
}

// The whitespace-separated words of the first line of `out` that starts with `start`, ignoring
// leading spaces; empty when there is none.
std::vector<std::string> RowWords(const std::string& out, const std::string& start) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.find_first_not_of(' ') == std::string::npos) continue;
    if (line.compare(line.find_first_not_of(' '), start.size(), start) != 0) continue;
    std::istringstream words(line);
    std::vector<std::string> v;
    for (std::string w; words >> w;) v.push_back(w);
    return v;
  }
  return {};
}

using Words = std::vector<std::string>;

// Sums field `what` of member `protocol` over the items of a by_class or by_range array.
double SumOf(const Json& rows, const std::string& protocol, const std::string& what) {
  double sum = 0;
  for (const Json& row : rows.items) sum += row[protocol][what].number;
  return sum;
}

TEST_F(CliEvaluate, ByClassPerClassAndSumsToTheProtocols) {
  const std::string args = "--pred " + root_ + "/pred --gt " + root_ + "/seq/labels --protocol all";
  Json plain = EvaluateJson(args);
  Json j = EvaluateJson(args + " --by-class");
  EXPECT_EQ(j.order, (std::vector<std::string>{"frames", "total", "by_class"}));
  // The scores are those without the flag.
  for (const char* p : {"dg", "pp", "pw", "gg"})
    for (const char* s : {"precision", "recall", "f1", "iou"})
      EXPECT_EQ(j["total"][p][s].number, plain["total"][p][s].number) << p << " " << s;
  const Json& rows = j["by_class"];
  ASSERT_EQ(rows.kind, Json::kArray);
  std::vector<double> ids;
  for (const Json& row : rows.items) ids.push_back(row["class"].number);
  EXPECT_EQ(ids, (std::vector<double>{0, 1, 10, 40, 48, 50, 70, 72}));
  const Json& car = rows.items[2];
  EXPECT_EQ(car.order, (std::vector<std::string>{"class", "name", "points", "predicted_ground",
                                                 "share", "dg", "pp", "pw", "gg"}));
  EXPECT_EQ(car["name"].text, "car");
  EXPECT_EQ(car["points"].number, 4);  // two in a, two in b
  EXPECT_EQ(car["predicted_ground"].number, 2);
  EXPECT_EQ(car["share"].number, 0.5);
  EXPECT_EQ(car["dg"].order, (std::vector<std::string>{"tp", "fp", "fn", "tn", "ignored"}));
  EXPECT_EQ(car["dg"]["fp"].number, 2);
  EXPECT_EQ(car["dg"]["tn"].number, 2);
  const Json& road = rows.items[3];
  EXPECT_EQ(road["name"].text, "road");
  EXPECT_EQ(road["points"].number, 5);
  EXPECT_EQ(road["predicted_ground"].number, 4);
  EXPECT_EQ(road["dg"]["fn"].number, 1);
  EXPECT_EQ(rows.items[6]["name"].text, "vegetation");
  EXPECT_EQ(rows.items[6]["pp"]["ignored"].number, 4);
  // Summed over the classes, each protocol's counts over both frames (frame a's hand counts plus
  // b's TP 2, FP 1): DG TP 5 FP 6 FN 2; PP and GG TP 5 FP 2 FN 2; PW TP 6 FP 4 FN 3.
  const std::map<std::string, std::array<double, 3>> expected = {
      {"dg", {5, 6, 2}}, {"pp", {5, 2, 2}}, {"pw", {6, 4, 3}}, {"gg", {5, 2, 2}}};
  for (const auto& [p, tp_fp_fn] : expected) {
    EXPECT_EQ(SumOf(rows, p, "tp"), tp_fp_fn[0]) << p;
    EXPECT_EQ(SumOf(rows, p, "fp"), tp_fp_fn[1]) << p;
    EXPECT_EQ(SumOf(rows, p, "fn"), tp_fp_fn[2]) << p;
  }
  // The summed protocols' totals are the scores of those sums.
  for (const char* p : {"dg", "gg"}) {
    const double tp = SumOf(rows, p, "tp"), fp = SumOf(rows, p, "fp"), fn = SumOf(rows, p, "fn");
    EXPECT_DOUBLE_EQ(j["total"][p]["precision"].number, tp / (tp + fp)) << p;
    EXPECT_DOUBLE_EQ(j["total"][p]["recall"].number, tp / (tp + fn)) << p;
  }
}

TEST_F(CliEvaluate, ByRangePerBand) {
  // Frame r: one point a band or two, at known horizontal ranges.
  fs::create_directories(root_ + "/range/labels");
  fs::create_directories(root_ + "/range/velodyne");
  WriteXyz(root_ + "/range/velodyne/r.bin", {{1, 0, -1.7f},
                                             {3, 4, -1.7f},
                                             {0, 9.99f, -1.0f},
                                             {10, 0, -1.7f},
                                             {0, -25, -1.7f},
                                             {-30, 0, 1.0f},
                                             {45, 0, -1.7f},
                                             {59.9f, 0, -1.7f},
                                             {60, 0, -1.7f},
                                             {100, 0, -1.7f}});
  WriteU32(root_ + "/range/labels/r.label", {40, 40, 10, 40, 48, 50, 72, 70, 40, 0});
  WriteU32(root_ + "/pred/r.label", {1, 0, 1, 1, 0, 1, 1, 1, 0, 0});
  Json j = EvaluateJson("--pred " + root_ + "/pred --gt " + root_ +
                        "/range/labels --protocol dg,gg --by-range");
  EXPECT_EQ(j.order, (std::vector<std::string>{"frames", "total", "by_range"}));
  const Json& bands = j["by_range"];
  ASSERT_EQ(bands.items.size(), 7u);
  struct Band {
    const char* name;
    double from, to, points, tp, fp, fn;
  };
  const Band expected[] = {{"0-5", 0, 5, 1, 1, 0, 0},     {"5-10", 5, 10, 2, 0, 1, 1},
                           {"10-20", 10, 20, 1, 1, 0, 0}, {"20-30", 20, 30, 1, 0, 0, 1},
                           {"30-40", 30, 40, 1, 0, 1, 0}, {"40-60", 40, 60, 2, 1, 1, 0},
                           {"60+", 60, -1, 2, 0, 0, 1}};
  for (size_t b = 0; b < 7; ++b) {
    const Band& e = expected[b];
    const Json& got = bands.items[b];
    SCOPED_TRACE(e.name);
    EXPECT_EQ(got["band"].text, e.name);
    EXPECT_EQ(got["from"].number, e.from);
    if (e.to < 0) {
      EXPECT_EQ(got.order, (std::vector<std::string>{"band", "from", "points", "dg", "gg"}));
    } else {
      EXPECT_EQ(got["to"].number, e.to);
    }
    EXPECT_EQ(got["points"].number, e.points);
    EXPECT_EQ(got["dg"]["tp"].number, e.tp);
    EXPECT_EQ(got["dg"]["fp"].number, e.fp);
    EXPECT_EQ(got["dg"]["fn"].number, e.fn);
  }
  // GG leaves out the vegetation at 59.9 m and the unlabeled point at 100 m.
  EXPECT_EQ(bands.items[5]["gg"]["fp"].number, 0);
  EXPECT_EQ(bands.items[5]["gg"]["ignored"].number, 1);
  EXPECT_EQ(bands.items[6]["gg"]["ignored"].number, 1);
  ExpectScores(j["total"]["dg"], 3.0 / 6, 3.0 / 6, 0.5, 3.0 / 9);
}

TEST_F(CliEvaluate, ByClassAndByRangeAgree) {
  Json j = EvaluateJson("--pred " + root_ + "/pred --gt " + root_ +
                        "/seq/labels --protocol all --by-class --by-range");
  EXPECT_EQ(j.order, (std::vector<std::string>{"frames", "total", "by_class", "by_range"}));
  for (const char* p : {"dg", "pp", "pw", "gg"})
    for (const char* what : {"tp", "fp", "fn", "tn", "ignored"})
      EXPECT_EQ(SumOf(j["by_class"], p, what), SumOf(j["by_range"], p, what)) << p << " " << what;
  double points = 0;
  for (const Json& band : j["by_range"].items) points += band["points"].number;
  EXPECT_EQ(points, double(kGtA.size() + kGtB.size()));
}

TEST_F(CliEvaluate, ByClassAndByRangeTables) {
  std::string out;
  ASSERT_EQ(Evaluate("--pred " + root_ + "/pred --gt " + root_ +
                         "/seq/labels --protocol dg,pp --by-class --by-range",
                     &out),
            0)
      << out;
  EXPECT_NE(out.find("By ground-truth class (semantickitti), summed over 2 frames"),
            std::string::npos)
      << out;
  EXPECT_EQ(RowWords(out, "class"), (Words{"class", "points", "pred.gnd", "share", "DG", "FP", "DG",
                                           "FN", "PP", "FP", "PP", "FN"}))
      << out;
  EXPECT_EQ(RowWords(out, "10 car"), (Words{"10", "car", "4", "2", "50.00%", "2", "0", "2", "0"}))
      << out;
  EXPECT_EQ(RowWords(out, "40 road"), (Words{"40", "road", "5", "4", "80.00%", "0", "1", "0", "1"}))
      << out;
  // PP scores no vegetation: '-'.
  EXPECT_EQ(RowWords(out, "70 vegetation"),
            (Words{"70", "vegetation", "4", "3", "75.00%", "3", "0", "-", "-"}))
      << out;
  // Scan points at x = 5 + i, y = 1: a's first five and all of b in 5-10 m, the rest 10-20 m.
  EXPECT_NE(out.find("By horizontal range sqrt(x^2 + y^2) in metres, summed over 2 frames"),
            std::string::npos)
      << out;
  EXPECT_EQ(RowWords(out, "5-10"), (Words{"5-10", "9", "4", "2", "2", "4", "2", "2"})) << out;
  EXPECT_EQ(RowWords(out, "10-20"), (Words{"10-20", "9", "1", "4", "0", "1", "0", "0"})) << out;
  EXPECT_EQ(RowWords(out, "0-5"), (Words{"0-5", "0", "0", "0", "0", "0", "0", "0"})) << out;
  // Without the flags, neither table.
  ASSERT_EQ(Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/seq/labels --protocol dg", &out),
            0);
  EXPECT_EQ(out.find("By "), std::string::npos) << out;
}

TEST_F(CliEvaluate, HelpStatesTheBandsAndTheRellisProtocol) {
  std::string out;
  ASSERT_EQ(Evaluate("--help", &out), 0);
  EXPECT_NE(out.find("[0,5) [5,10) [10,20) [20,30) [30,40) [40,60) [60,inf) m"), std::string::npos)
      << out;
  EXPECT_NE(out.find("--ontology O"), std::string::npos) << out;
  EXPECT_NE(out.find("void (0) not scored"), std::string::npos) << out;
}

// A RELLIS-3D frame: scan and labels in one folder, as RELLIS-3D keeps them.
class CliEvaluateRellis : public CliEvaluate {
 protected:
  void SetUp() override {
    CliEvaluate::SetUp();
    fs::create_directories(root_ + "/rellis");
    // void (predicted ground, not), grass TP, dirt FN, tree FP, bush TN, concrete TP, person TN,
    // mud TP, asphalt FN: TP 3, FP 1, FN 2, TN 2, 2 void left out.
    WriteU32(root_ + "/rellis/x.label", {0, 0, 3, 1, 4, 19, 23, 17, 33, 10});
    WriteU32(root_ + "/pred/x.label", {1, 0, 1, 0, 1, 0, 1, 0, 1, 0});
    std::vector<std::array<float, 3>> points;
    for (int i = 0; i < 10; ++i) points.push_back({float(i * 7), 0, -1.0f});  // 0, 7, ... 63 m
    WriteXyz(root_ + "/rellis/x.bin", points);
    gt_ = " --gt " + root_ + "/rellis/x.label --pred " + root_ + "/pred";
  }
  std::string gt_;
};

TEST_F(CliEvaluateRellis, VoidLeftOut) {
  Json j = EvaluateJson(gt_ + " --ontology rellis3d");
  EXPECT_EQ(j["frames"].items[0].order, (std::vector<std::string>{"name", "rellis"}));
  EXPECT_EQ(j["total"].order, std::vector<std::string>{"rellis"});
  ExpectScores(j["total"]["rellis"], 3.0 / 4, 3.0 / 5, F1(3.0 / 4, 3.0 / 5), 3.0 / 6);
  // --protocol rellis and all say the same.
  for (const char* p : {"rellis", "all"}) {
    Json k = EvaluateJson(gt_ + " --ontology rellis3d --protocol " + p);
    ExpectScores(k["total"]["rellis"], 3.0 / 4, 3.0 / 5, F1(3.0 / 4, 3.0 / 5), 3.0 / 6);
  }
  std::string out;
  ASSERT_EQ(Evaluate(gt_ + " --ontology rellis3d", &out), 0) << out;
  EXPECT_NE(out.find("RELLIS (RELLIS-3D): ground 1 3 6 10 23 31 33, void (0) not scored"),
            std::string::npos)
      << out;
  EXPECT_EQ(RowWords(out, "total"), (Words{"total", "75.00%", "60.00%", "66.67%", "50.00%"}))
      << out;
}

TEST_F(CliEvaluateRellis, ByClassNamesAndByRangeFromTheLabelsFolder) {
  Json j = EvaluateJson(gt_ + " --ontology rellis3d --by-class --by-range");
  const Json& rows = j["by_class"];
  std::vector<std::string> names;
  for (const Json& row : rows.items) names.push_back(row["name"].text);
  EXPECT_EQ(names, (std::vector<std::string>{"void", "dirt", "grass", "tree", "asphalt", "person",
                                             "bush", "concrete", "mud"}));
  const Json& void_row = rows.items[0];
  EXPECT_EQ(void_row["points"].number, 2);
  EXPECT_EQ(void_row["predicted_ground"].number, 1);
  EXPECT_EQ(void_row["rellis"]["ignored"].number, 2);
  EXPECT_EQ(rows.items[3]["rellis"]["fp"].number, 1);  // tree
  EXPECT_EQ(rows.items[4]["rellis"]["fn"].number, 1);  // asphalt
  EXPECT_EQ(SumOf(rows, "rellis", "tp"), 3);
  EXPECT_EQ(SumOf(rows, "rellis", "fp"), 1);
  EXPECT_EQ(SumOf(rows, "rellis", "fn"), 2);
  // The scan beside the labels: points at 0, 7, 14, ..., 63 m.
  const Json& bands = j["by_range"];
  ASSERT_EQ(bands.items.size(), 7u);
  const std::vector<double> points = {1, 1, 1, 2, 1, 3, 1};
  for (size_t b = 0; b < 7; ++b) EXPECT_EQ(bands.items[b]["points"].number, points[b]) << b;
  EXPECT_EQ(SumOf(bands, "rellis", "tp"), 3);
  EXPECT_EQ(SumOf(bands, "rellis", "ignored"), 2);
  std::string out;
  ASSERT_EQ(Evaluate(gt_ + " --ontology rellis3d --by-class", &out), 0) << out;
  EXPECT_NE(out.find("By ground-truth class (rellis3d)"), std::string::npos) << out;
  EXPECT_EQ(RowWords(out, "0 void"), (Words{"0", "void", "2", "1", "50.00%", "-", "-"})) << out;
  EXPECT_EQ(RowWords(out, "3 grass"), (Words{"3", "grass", "1", "1", "100.00%", "0", "0"})) << out;
}

TEST_F(CliEvaluateRellis, Errors) {
  std::string out;
  EXPECT_NE(Evaluate(gt_ + " --ontology kitti", &out), 0);
  EXPECT_NE(out.find("unknown ontology 'kitti' (known: semantickitti, rellis3d)"),
            std::string::npos)
      << out;
  EXPECT_NE(Evaluate(gt_ + " --ontology rellis3d --protocol pw", &out), 0);
  EXPECT_NE(out.find("protocol 'pw' scores semantickitti labels, not rellis3d ones"),
            std::string::npos)
      << out;
  EXPECT_NE(Evaluate(gt_ + " --protocol rellis", &out), 0);
  EXPECT_NE(out.find("protocol 'rellis' scores rellis3d labels, not semantickitti ones"),
            std::string::npos)
      << out;
  // Without --ontology the labels are read as SemanticKITTI ones, under DG.
  EXPECT_EQ(Evaluate(gt_, &out), 0) << out;
  EXPECT_NE(out.find("DG (DipG-Seg)"), std::string::npos) << out;
}

TEST_F(CliEvaluate, ByRangeErrors) {
  // Ground truth with no scan anywhere: names the file, where it looked, and --scans.
  fs::create_directories(root_ + "/flat");
  fs::copy_file(root_ + "/seq/labels/a.label", root_ + "/flat/a.label");
  std::string out;
  EXPECT_NE(
      Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/flat --protocol dg --by-range", &out),
      0);
  EXPECT_NE(out.find("--by-range needs each point's x and y, but no scan was found for " + root_ +
                     "/flat/a.label (looked for " + root_ + "/flat/a.bin)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("pass --scans DIR holding a.bin"), std::string::npos) << out;
  // --scans names it; a scan of the wrong size is named with both counts.
  WriteScan(root_ + "/flat/a.bin", {-1.7f, -1.7f, -1.7f});
  EXPECT_NE(
      Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/flat --protocol dg --by-range", &out),
      0);
  EXPECT_NE(out.find("scan " + root_ + "/flat/a.bin has 3 points but ground truth " + root_ +
                     "/flat/a.label has 14 labels"),
            std::string::npos)
      << out;
  EXPECT_EQ(Evaluate("--pred " + root_ + "/pred --gt " + root_ + "/flat --protocol dg --by-range" +
                         " --scans " + root_ + "/seq/velodyne",
                     &out),
            0)
      << out;
}

TEST(CliEvaluateRealScan, GroundTruthAgainstItself) {
  LPIR_REQUIRE_DATA("kitti/07/labels/000964.label");
  LPIR_REQUIRE_DATA("kitti/07/velodyne/000964.bin");
  // A prediction that is exactly the six ground classes: perfect under DG, PP and GG; under PW
  // the low vegetation it leaves out costs recall but no precision.
  std::string gt = test::DataFile("kitti/07/labels/000964.label");
  std::ifstream in(gt, std::ios::binary);
  std::vector<uint32_t> labels(fs::file_size(gt) / 4);
  in.read(reinterpret_cast<char*>(labels.data()), std::streamsize(labels.size() * 4));
  std::vector<uint32_t> pred(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) pred[i] = IsGroundClass(labels[i]) ? 1 : 0;
  const test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  WriteU32(dir + "/000964.label", pred);
  std::string out;
  ASSERT_EQ(test::RunCommand("'" + test::CliPath() + "' evaluate --pred " + dir + " --gt " +
                                 test::DataFile("kitti/07/labels") + " --protocol all --json",
                             &out),
            0)
      << out;
  Json j;
  ASSERT_TRUE(JsonReader(out).ReadAll(&j)) << out;
  for (const char* p : {"dg", "pp", "gg"}) ExpectScores(j["total"][p], 1, 1, 1, 1);
  EXPECT_EQ(j["total"]["pw"]["precision"].number, 1.0);
  EXPECT_LT(j["total"]["pw"]["recall"].number, 1.0);
  EXPECT_GT(j["total"]["pw"]["recall"].number, 0.9);
}

TEST(CliEvaluateRealScan, RellisOs1SegmentedScoresF1AtLeast94) {
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.bin");
  LPIR_REQUIRE_DATA("rellis3d/os1/000104.label");
  const test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  const std::string cli = "'" + test::CliPath() + "'";
  std::string out;
  ASSERT_EQ(test::RunCommand(cli + " segment " + test::DataFile("rellis3d/os1/000104.bin") +
                                 " --sensor os1-64 --backend cpu --quiet --out " + dir,
                             &out),
            0)
      << out;
  ASSERT_EQ(test::RunCommand(cli + " evaluate --pred " + dir + " --gt " +
                                 test::DataFile("rellis3d/os1/000104.label") +
                                 " --ontology rellis3d --by-class --by-range --json",
                             &out),
            0)
      << out;
  Json j;
  ASSERT_TRUE(JsonReader(out).ReadAll(&j)) << out;
  const Json& s = j["total"]["rellis"];
  // Measured: P 95.87 %, R 94.28 %, F1 95.07 %.
  EXPECT_GE(s["f1"].number, 0.94) << out;
  EXPECT_GT(s["precision"].number, 0.9) << out;
  EXPECT_GT(s["recall"].number, 0.9) << out;
  // The 53,364 no-return points are void: left out, and at 0 m.
  EXPECT_EQ(j["by_class"].items[0]["name"].text, "void");
  EXPECT_GE(j["by_range"].items[0]["rellis"]["ignored"].number, 53364);
}

}  // namespace
}  // namespace lpir
