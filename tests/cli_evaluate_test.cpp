// lpir-gseg evaluate, run as a process on small label files written here: the JSON values of every
// protocol, folder and file arguments, the table, and the error exits.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
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
  // Missing prediction: names both files.
  fs::remove(root_ + "/pred/b.label");
  EXPECT_NE(Evaluate(pred + gt + " --protocol dg", &out), 0);
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
  EXPECT_NE(Evaluate(pred + gt, &out), 0);
  EXPECT_NE(out.find("--protocol is required"), std::string::npos) << out;
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
  std::string dir = test::TempDir();
  WriteU32(dir + "/000964.label", pred);
  struct Cleanup {
    std::string path;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } cleanup{dir};
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

}  // namespace
}  // namespace lpir
