// Accuracy on the two labelled SemanticKITTI scans (HDL-64E profile, the whole pipeline): DG
// precision and F1 must stay above floors, and every protocol must give finite scores in [0, 1].
// Skips with a message when ../shared/data is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "host/eval/metrics.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "host/segmenter.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

// DG floors in percent. The project's promise (issue 2): precision and F1 at least 95.0 on each
// labelled scan; 000964 holds more than that, so its floors sit just under today's values
// (P 99.35, F1 95.56) to catch a regression early. Results are deterministic.
constexpr double kPrecisionFloor964 = 99.0;
constexpr double kF1Floor964 = 95.3;
constexpr double kPrecisionFloor056 = 95.0;
constexpr double kF1Floor056 = 95.0;

struct Scan {
  const char* name;  // for properties
  const char* cloud;
  const char* labels;
  double precision_floor, f1_floor;
};

const Scan kScans[] = {
    {"07_000964", "kitti/07/velodyne/000964.bin", "kitti/07/labels/000964.label",
     kPrecisionFloor964, kF1Floor964},
    {"unknown_000056", "kitti/unknown/velodyne/000056.bin", "kitti/unknown/labels/000056.label",
     kPrecisionFloor056, kF1Floor056},
};

// gtest prints the parameter in the test's name and description: the scan's name, not its bytes.
void PrintTo(const Scan& scan, std::ostream* os) { *os << scan.name; }

class AccuracyKitti : public ::testing::TestWithParam<Scan> {};

TEST_P(AccuracyKitti, ScoresStayAboveTheFloors) {
  const Scan& scan = GetParam();
  LPIR_REQUIRE_DATA(scan.cloud);
  LPIR_REQUIRE_DATA(scan.labels);
  const Cloud cloud = ReadKittiBin(test::DataFile(scan.cloud));
  const std::vector<uint32_t> truth = ReadLabelFile(test::DataFile(scan.labels), cloud.size());
  Segmenter seg(LoadSensorProfile("hdl64e", LPIR_SENSORS_DIR),
                SegmenterOptions::For(Backend::kCpu));
  const Frame& f = seg.Segment(cloud);
  ASSERT_EQ(f.label.size(), cloud.size());
  const Labels pred(f.label.begin(), f.label.end());
  std::vector<float> z(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) z[i] = cloud.z(i);

  for (Protocol protocol : AllProtocols()) {
    const std::string name = ProtocolName(protocol);
    SCOPED_TRACE("protocol " + name);
    const Counts c = CountFrame(protocol, pred, truth, &z);
    const Scores s = ScoreCounts(c);
    EXPECT_GT(c.tp, 0u);
    for (double v : {s.precision, s.recall, s.f1, s.iou}) {
      EXPECT_TRUE(std::isfinite(v));
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
    }
    RecordProperty(name + "_precision", std::to_string(100 * s.precision));
    RecordProperty(name + "_recall", std::to_string(100 * s.recall));
    RecordProperty(name + "_f1", std::to_string(100 * s.f1));
    RecordProperty(name + "_iou", std::to_string(100 * s.iou));
    std::printf("%s %s: P %.2f R %.2f F1 %.2f IoU %.2f\n", scan.name, name.c_str(),
                100 * s.precision, 100 * s.recall, 100 * s.f1, 100 * s.iou);
    if (protocol == Protocol::kDG) {
      EXPECT_GE(100 * s.precision, scan.precision_floor);
      EXPECT_GE(100 * s.f1, scan.f1_floor);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scans, AccuracyKitti, ::testing::ValuesIn(kScans),
                         [](const ::testing::TestParamInfo<Scan>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace lpir
