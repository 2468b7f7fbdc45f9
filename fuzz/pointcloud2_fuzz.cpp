// Fuzz target of the PointCloud2 CDR parser and decoder (host/drive/pointcloud2.h): any bytes as
// one message either throw IoError or parse into a message that serializes and parses back
// equal; a message that decodes gives one point per width x height with its ring checked, and
// split by label (SplitByLabel) gives clouds whose fields are all aligned, as many points as it
// had, the labelled one decoding to the very same cloud. Anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/cloud_checks.h"
#include "fuzz/fuzz_file.h"
#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"

namespace {

bool SameMessage(const lpir::PointCloud2& a, const lpir::PointCloud2& b) {
  if (a.fields.size() != b.fields.size()) return false;
  for (size_t i = 0; i < a.fields.size(); ++i) {
    const lpir::PointField &x = a.fields[i], &y = b.fields[i];
    if (x.name != y.name || x.offset != y.offset || x.datatype != y.datatype || x.count != y.count)
      return false;
  }
  return a.stamp_sec == b.stamp_sec && a.stamp_nanosec == b.stamp_nanosec &&
         a.frame_id == b.frame_id && a.height == b.height && a.width == b.width &&
         a.is_bigendian == b.is_bigendian && a.point_step == b.point_step &&
         a.row_step == b.row_step && a.data == b.data && a.is_dense == b.is_dense;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lpir;
  const std::string where = "fuzz message";
  PointCloud2 msg;
  try {
    msg = ParseCdrPointCloud2(where, data, size);
  } catch (const IoError&) {
    return 0;
  }
  const std::vector<uint8_t> again = SerializeCdrPointCloud2(msg);
  LPIR_FUZZ_CHECK(SameMessage(msg, ParseCdrPointCloud2(where, again.data(), again.size())));
  Cloud cloud;
  try {
    cloud = CloudFromPointCloud2(where, msg);
  } catch (const IoError&) {
    return 0;
  }
  fuzz::CheckCloudShape(cloud);
  LPIR_FUZZ_CHECK(cloud.size() == uint64_t(msg.width) * msg.height);
  Labels labels(cloud.size());
  for (size_t i = 0; i < labels.size(); ++i) labels[i] = uint8_t(i % 2);
  LabelledClouds split;
  try {
    split = SplitByLabel(where, msg, labels);
  } catch (const IoError&) {
    return 0;  // a `label` field already, overlapping fields, or a row_step past 32 bits
  }
  for (const PointCloud2* c : {&split.labelled, &split.ground, &split.nonground}) {
    LPIR_FUZZ_CHECK(c->point_step % 4 == 0);
    for (const PointField& f : c->fields) {
      const uint32_t size = f.datatype <= 2 ? 1 : f.datatype <= 4 ? 2 : f.datatype <= 7 ? 4 : 8;
      LPIR_FUZZ_CHECK(f.offset % size == 0 && c->point_step % size == 0);
    }
  }
  LPIR_FUZZ_CHECK(uint64_t(split.ground.width) + split.nonground.width == cloud.size());
  LPIR_FUZZ_CHECK(split.ground.width == cloud.size() / 2);
  fuzz::CheckSameCloud(cloud, CloudFromPointCloud2(where, split.labelled), false);
  return 0;
}
