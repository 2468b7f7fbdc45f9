// segment --report FILE.csv|.json: a row per frame whose figures agree with the labels written,
// invalid points counted by reason with prepare's rule (the reasons sum to the points labelled
// invalid), failed files listed with their error; --quiet prints nothing on success.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli/invalid_reasons.h"
#include "apps/sim/scene.h"
#include "host/api/segmenter.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// Two rings of road around the sensor.
Cloud Road(int points_per_ring) {
  Cloud c;
  for (int k = 0; k < points_per_ring; ++k) {
    const float a = float(k) * 6.2831853f / float(points_per_ring);
    c.Push(8.0f * std::cos(a), 8.0f * std::sin(a), -1.73f, 0.3f);
    c.Push(6.0f * std::cos(a), 6.0f * std::sin(a), -1.73f, 0.3f);
  }
  return c;
}

// A simulated hdl64e street scan (every point valid).
Cloud Scan(uint32_t seed) {
  SimOptions options;
  options.seed = seed;
  return Simulate(LoadSensorProfile("hdl64e", test::SensorsDir()), options).cloud;
}

// `base` plus invalid points: 3 not finite, 2 at the origin (one of them subnormal, flushed), 4 out
// of range (near, far, beyond the range's z bound, r2 right above max); and one valid point whose
// intensity is NaN (intensity is not read).
Cloud WithInvalidPoints(Cloud c) {
  c.Push(kNan, 1, 1, 0);
  c.Push(1, kInf, 1, 0);
  c.Push(5, 5, -kInf, 0);
  c.Push(5, 5, -1, kNan);
  c.Push(0, 0, 0, 0.5f);
  c.Push(1e-40f, 0, 0, 0);
  c.Push(1, 1, -1, 0);       // 1.4 m: the car
  c.Push(200, 0, -1, 0);     // beyond 120 m
  c.Push(10, 0, 130, 0);     // z^2 beyond max_range2
  c.Push(0, 120.01f, 0, 0);  // just beyond
  return c;
}

size_t CountWhy(const Frame& f, uint8_t why) {
  size_t n = 0;
  for (uint32_t i = 0; i < f.n; ++i) n += f.why[i] == why;
  return n;
}

TEST(InvalidReasons, SumToThePointsStageOneMarksInvalid) {
  Segmenter seg(LoadSensorProfile("hdl64e", test::SensorsDir()),
                SegmenterOptions::For(Backend::kCpu));
  const Cloud c = WithInvalidPoints(Scan(1));
  const InvalidReasons r = CountInvalidReasons(c, seg.params(), true);
  EXPECT_EQ(r.not_finite, 3u);
  EXPECT_EQ(r.at_origin, 2u);
  EXPECT_EQ(r.out_of_range, 4u);
  EXPECT_EQ(r.bad_ring, 0u);
  EXPECT_EQ(r.total(), CountWhy(seg.Segment(c), kWhyInvalid));
}

TEST(InvalidReasons, RingOutsideTheBeamsIsItsOwnReason) {
  Segmenter seg(LoadSensorProfile("hdl64e", test::SensorsDir()),
                SegmenterOptions::For(Backend::kCpu));
  Cloud c = WithInvalidPoints(Road(300));
  c.ring.assign(c.size(), 10);
  c.ring[0] = -1;
  c.ring[1] = 64;             // hdl64e: rings 0..63
  c.ring[c.size() - 9] = 64;  // the NaN point: counted as not finite only
  const InvalidReasons r = CountInvalidReasons(c, seg.params(), true);
  EXPECT_EQ(r.bad_ring, 2u);
  EXPECT_EQ(r.not_finite, 3u);
  EXPECT_EQ(r.total(), CountWhy(seg.Segment(c), kWhyInvalid));
}

// Counted from the frame's why (what segment does), the reasons are those of every point.
TEST(InvalidReasons, FromTheFramesWhyTheSameAsFromEveryPoint) {
  Segmenter seg(LoadSensorProfile("hdl64e", test::SensorsDir()),
                SegmenterOptions::For(Backend::kCpu));
  Cloud c = WithInvalidPoints(Scan(1));
  c.ring.assign(c.size(), 10);
  c.ring[0] = -1;
  c.ring[c.size() / 2] = 64;
  const std::vector<uint8_t> why = seg.Segment(c).why;
  for (bool rings_read : {true, false}) {
    const InvalidReasons all = CountInvalidReasons(c, seg.params(), rings_read);
    const InvalidReasons from_why = CountInvalidReasons(c, seg.params(), rings_read, why);
    EXPECT_EQ(from_why.not_finite, all.not_finite);
    EXPECT_EQ(from_why.at_origin, all.at_origin);
    EXPECT_EQ(from_why.out_of_range, all.out_of_range);
    EXPECT_EQ(from_why.bad_ring, all.bad_ring);
  }
  EXPECT_EQ(CountInvalidReasons(c, seg.params(), true, why).bad_ring, 2u);
}

// A CSV line's fields (no quoted fields expected but the error column's).
std::vector<std::string> CsvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        fields.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      fields.emplace_back();
    } else {
      fields.back() += ch;
    }
  }
  return fields;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

size_t Ground(const std::string& label_file, size_t points) {
  size_t g = 0;
  for (uint32_t l : ReadLabelFile(label_file, points)) g += l;
  return g;
}

Cloud RoadWithInvalidPoints() { return WithInvalidPoints(Scan(1)); }

// Writes road.bin (a scan with invalid points), plain.bin (a scan) and broken.bin (not a whole
// point) in `dir`.
void WriteInputs(const std::string& dir) {
  WriteKittiBin(dir + "/road.bin", RoadWithInvalidPoints());
  WriteKittiBin(dir + "/plain.bin", Scan(2));
  std::ofstream(dir + "/broken.bin", std::ios::binary) << "12345";
}

std::string SegmentCommand(const std::string& dir, const std::string& extra) {
  return test::CliPath() + " segment " + dir + "/road.bin " + dir + "/plain.bin " + dir +
         "/broken.bin --sensor hdl64e --backend cpu --out " + dir + "/out " + extra;
}

TEST(CliReport, CsvHasAHeaderAndARowPerFileAgreeingWithTheLabels) {
  test::ScopedDir dir;
  WriteInputs(dir.path);
  std::string log;
  ASSERT_EQ(test::RunCommand(SegmentCommand(dir.path, "--report " + dir.path + "/r.csv"), &log), 1)
      << log;
  const std::vector<std::string> lines = Lines(test::ReadFileBytes(dir.path + "/r.csv"));
  ASSERT_EQ(lines.size(), 4u) << test::ReadFileBytes(dir.path + "/r.csv");
  EXPECT_EQ(lines[0],
            "input,sequence,stamp_ns,topic,points,ground,ground_fraction,invalid,"
            "invalid_not_finite,invalid_at_origin,invalid_out_of_range,invalid_bad_ring,ms,"
            "sensor_height,k_xz,k_yz,mount_estimated,backend,device,error");
  const std::vector<std::string> road = CsvFields(lines[1]), plain = CsvFields(lines[2]),
                                 broken = CsvFields(lines[3]);
  ASSERT_EQ(road.size(), 20u);
  ASSERT_EQ(plain.size(), 20u);
  ASSERT_EQ(broken.size(), 20u);
  EXPECT_EQ(road[0], dir.path + "/road.bin");
  EXPECT_EQ(road[1] + road[2] + road[3], "");  // a file: no sequence, stamp or topic
  const size_t n = RoadWithInvalidPoints().size();
  EXPECT_EQ(road[4], std::to_string(n));
  const size_t ground = Ground(dir.path + "/out/road.label", n);
  EXPECT_GT(ground, 0u);
  EXPECT_EQ(road[5], std::to_string(ground));
  EXPECT_NEAR(std::stod(road[6]), double(ground) / double(n), 1e-6);
  EXPECT_EQ(road[7], "9");
  EXPECT_EQ(road[8], "3");
  EXPECT_EQ(road[9], "2");
  EXPECT_EQ(road[10], "4");
  EXPECT_EQ(road[11], "0");
  EXPECT_GT(std::stod(road[12]), 0.0);
  EXPECT_EQ(road[13], "1.7300");  // hdl64e's mount, fixed
  EXPECT_EQ(road[14], "0.000000");
  EXPECT_EQ(road[15], "0.000000");
  EXPECT_EQ(road[16], "0");
  EXPECT_EQ(road[17], "cpu");
  EXPECT_EQ(road[18], "CPU reference");
  EXPECT_EQ(road[19], "");
  const size_t plain_n = Scan(2).size();
  EXPECT_EQ(plain[4], std::to_string(plain_n));
  EXPECT_EQ(plain[5], std::to_string(Ground(dir.path + "/out/plain.label", plain_n)));
  EXPECT_EQ(plain[7], "0");
  EXPECT_EQ(broken[0], dir.path + "/broken.bin");
  EXPECT_EQ(broken[4], "0");
  EXPECT_NE(broken[19].find(dir.path + "/broken.bin"), std::string::npos) << broken[19];
  EXPECT_NE(broken[19].find("16-byte"), std::string::npos) << broken[19];
}

// `--set mount=per_frame`: each frame's own mount in the report (the plain scan is simulated from
// hdl64e's 1.73 m), and its median in the summary line.
TEST(CliReport, PerFrameMountsAreReportedAndSummed) {
  test::ScopedDir dir;
  WriteInputs(dir.path);
  std::string log;
  ASSERT_EQ(
      test::RunCommand(
          SegmentCommand(dir.path, "--set mount=per_frame --report " + dir.path + "/r.csv"), &log),
      1)
      << log;
  const std::vector<std::string> lines = Lines(test::ReadFileBytes(dir.path + "/r.csv"));
  ASSERT_EQ(lines.size(), 4u);
  const std::vector<std::string> plain = CsvFields(lines[2]);
  ASSERT_EQ(plain.size(), 20u);
  EXPECT_NEAR(std::stod(plain[13]), 1.73, 0.12);
  EXPECT_EQ(plain[16], "1");
  EXPECT_NE(log.find("sensor height estimated on "), std::string::npos) << log;
}

TEST(CliReport, JsonParsesAndHoldsTheSameFigures) {
  LPIR_REQUIRE_PYTHON_JSON();
  test::ScopedDir dir;
  WriteInputs(dir.path);
  const std::string json = dir.path + "/r.json";
  std::string log;
  ASSERT_EQ(test::RunCommand(SegmentCommand(dir.path, "--report " + json), &log), 1) << log;
  // One line per frame: input name, points, ground, invalid, the reasons' sum, error or "-";
  // then the summary's frames and failed.
  const std::string script =
      "import json,os,sys\n"
      "d=json.load(open(sys.argv[1]))\n"
      "for f in d['frames']:\n"
      "  r=[f[k] for k in ('invalid_not_finite','invalid_at_origin','invalid_out_of_range',"
      "'invalid_bad_ring')]\n"
      "  assert f['sequence'] is None and f['topic'] is None and f['backend']=='cpu'\n"
      "  print(os.path.basename(f['input']),f['points'],f['ground'],f['invalid'],sum(r),"
      "'-' if f['error'] is None else 'error')\n"
      "s=d['summary']\n"
      "print(s['frames'],s['failed'],s['device'])\n";
  std::ofstream(dir.path + "/check.py") << script;
  std::string parsed;
  ASSERT_EQ(test::RunCommand("python3 " + dir.path + "/check.py " + json, &parsed), 0)
      << parsed << test::ReadFileBytes(json);
  const size_t n = RoadWithInvalidPoints().size(), plain_n = Scan(2).size();
  const std::string expected = "road.bin " + std::to_string(n) + " " +
                               std::to_string(Ground(dir.path + "/out/road.label", n)) +
                               " 9 9 -\n" + "plain.bin " + std::to_string(plain_n) + " " +
                               std::to_string(Ground(dir.path + "/out/plain.label", plain_n)) +
                               " 0 0 -\n" + "broken.bin 0 0 0 0 error\n" + "2 1 CPU reference\n";
  EXPECT_EQ(parsed, expected) << test::ReadFileBytes(json);
}

TEST(CliReport, VerboseLinesHoldTheReasons) {
  test::ScopedDir dir;
  WriteKittiBin(dir.path + "/road.bin", RoadWithInvalidPoints());
  std::string log;
  ASSERT_EQ(
      test::RunCommand(test::CliPath() + " segment " + dir.path +
                           "/road.bin --sensor hdl64e --backend cpu --verbose --out " + dir.path,
                       &log),
      0)
      << log;
  EXPECT_NE(log.find("road: " + std::to_string(RoadWithInvalidPoints().size()) + " points"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("(9 invalid: 3 NaN/Inf, 2 at the origin, 4 out of range)"), std::string::npos)
      << log;
}

TEST(CliReport, QuietPrintsNothingOnSuccessAndStillWritesTheReport) {
  test::ScopedDir dir;
  WriteKittiBin(dir.path + "/a.bin", Road(400));
  WriteKittiBin(dir.path + "/b.bin", RoadWithInvalidPoints());
  std::string log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " segment " + dir.path + "/a.bin " + dir.path +
                                 "/b.bin --sensor hdl64e --backend cpu --quiet --out " + dir.path +
                                 "/out --report " + dir.path + "/r.csv",
                             &log),
            0)
      << log;
  EXPECT_EQ(log, "");
  EXPECT_EQ(Lines(test::ReadFileBytes(dir.path + "/r.csv")).size(), 3u);
}

TEST(CliReport, ANameOtherThanCsvOrJsonIsRefused) {
  test::ScopedDir dir;
  WriteKittiBin(dir.path + "/a.bin", Road(400));
  std::string log;
  EXPECT_EQ(test::RunCommand(test::CliPath() + " segment " + dir.path +
                                 "/a.bin --sensor hdl64e --backend cpu --out " + dir.path +
                                 " --report " + dir.path + "/r.txt",
                             &log),
            2);
  EXPECT_NE(log.find("--report must name a .csv or .json file"), std::string::npos) << log;
}

TEST(CliReport, AReportThatCannotBeCreatedIsNamed) {
  test::ScopedDir dir;
  WriteKittiBin(dir.path + "/a.bin", Road(400));
  std::string log;
  EXPECT_EQ(test::RunCommand(test::CliPath() + " segment " + dir.path +
                                 "/a.bin --sensor hdl64e --backend cpu --out " + dir.path +
                                 " --report " + dir.path + "/no/such/dir/r.csv",
                             &log),
            4);
  EXPECT_NE(log.find(dir.path + "/no/such/dir/r.csv"), std::string::npos) << log;
}

TEST(CliReport, NamesWithCommasAndQuotesSurviveBothFormats) {
  test::ScopedDir dir;
  const std::string name = dir.path + "/we\"ird,name.bin";
  WriteKittiBin(name, Road(400));
  std::string log;
  for (const char* report : {"/r.csv", "/r.json"}) {
    ASSERT_EQ(test::RunCommand(test::CliPath() + " segment '" + name +
                                   "' --sensor hdl64e --backend cpu --quiet --out " + dir.path +
                                   " --report " + dir.path + report,
                               &log),
              0)
        << log;
  }
  const std::vector<std::string> lines = Lines(test::ReadFileBytes(dir.path + "/r.csv"));
  ASSERT_EQ(lines.size(), 2u);
  const std::vector<std::string> row = CsvFields(lines[1]);
  ASSERT_EQ(row.size(), 20u) << lines[1];
  EXPECT_EQ(row[0], name);
  LPIR_REQUIRE_PYTHON_JSON();
  std::ofstream(dir.path + "/check.py")
      << "import json,sys\nprint(json.load(open(sys.argv[1]))['frames'][0]['input'])\n";
  std::string parsed;
  ASSERT_EQ(test::RunCommand("python3 " + dir.path + "/check.py " + dir.path + "/r.json", &parsed),
            0)
      << parsed;
  EXPECT_EQ(parsed, name + "\n");
}

TEST(CliReport, JsonOfANameThatIsNotUtf8StillParses) {
  LPIR_REQUIRE_PYTHON_JSON();
  test::ScopedDir dir;
  const std::string name = dir.path + "/caf\xc3\xa9 \xff\xc3.bin";  // UTF-8, then two bad bytes
  WriteKittiBin(name, Road(400));
  std::string log;
  ASSERT_EQ(test::RunCommand(test::CliPath() + " segment '" + name +
                                 "' --sensor hdl64e --backend cpu --quiet --out " + dir.path +
                                 " --report " + dir.path + "/r.json",
                             &log),
            0)
      << log;
  std::ofstream(dir.path + "/check.py")
      << "import json,os,sys\n"
         "f=json.load(open(sys.argv[1],encoding='utf-8'))['frames'][0]\n"
         "print(os.path.basename(f['input'])=='caf\\u00e9 \\ufffd\\ufffd.bin',f['points'])\n";
  std::string parsed;
  ASSERT_EQ(test::RunCommand("python3 " + dir.path + "/check.py " + dir.path + "/r.json", &parsed),
            0)
      << parsed << test::ReadFileBytes(dir.path + "/r.json");
  EXPECT_EQ(parsed, "True 800\n");
}

}  // namespace
}  // namespace lpir
