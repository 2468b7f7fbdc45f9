// Writes the seed corpus of every fuzz target: small valid files from the project's own writers
// and hand-made edge cases (comments, CRLF, skipped and multi-count fields, NaN/Inf, 0 points,
// other elements, continuation lines, calibration keys), one folder per target.
// Usage: make_corpus OUT_DIR  (fuzz/corpus/ holds its output, checked by ctest: fuzz.corpus).
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "host/io/file_bytes.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/pcd.h"
#include "host/io/ply.h"
#include "host/io/sensor_profile.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

void Text(const std::string& path, const std::string& text) {
  WriteFileBytes(path, text.data(), text.size());
}
// A literal's bytes, NULs included.
template <size_t N>
std::string Raw(const char (&literal)[N]) {
  return std::string(literal, N - 1);
}

// A few points with every kind of value a scan holds: road, obstacle, NaN, Inf, the origin,
// a far point, a negative intensity.
Cloud Points(bool with_ring) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Cloud c;
  c.Push(5.25f, -1.5f, -1.73f, 0.25f);
  c.Push(-3.0f, 7.125f, 0.5f, 0.75f);
  c.Push(nan, 1.0f, 2.0f, 0.0f);
  c.Push(1.0f, inf, -1.0f, 1.0f);
  c.Push(0.0f, 0.0f, 0.0f, 0.0f);
  c.Push(1e30f, -1e-30f, 3.0f, -2.0f);
  if (with_ring) c.ring = {0, 5, 15, 1, 2147483647, 7};
  return c;
}

void KittiBin(const std::string& dir) {
  WriteKittiBin(dir + "/points.bin", Points(false));
  WriteKittiBin(dir + "/nuscenes.bin", Points(true), BinLayout::kNuScenes5);
  Cloud one;
  one.Push(10.0f, 0.0f, -1.7f, 0.5f);
  WriteKittiBin(dir + "/one_point.bin", one);
  Text(dir + "/empty.bin", "");
  Text(dir + "/truncated.bin", std::string(21, '\1'));
}

void LabelFile(const std::string& dir) {
  WriteLabelFile(dir + "/labels.label", {40, 48, 0, 10, 1u << 16 | 40, 0xFFFFFFFFu});
  WriteLabelFile(dir + "/one.label", {72});
  Text(dir + "/ragged.label", "abc");
}

void Pcd(const std::string& dir) {
  const Cloud ring = Points(true), plain = Points(false);
  const Labels labels = {1, 0, 0, 1, 0, 1};
  WritePcd(dir + "/ascii_ring.pcd", ring, nullptr, false);
  WritePcd(dir + "/binary_ring.pcd", ring, nullptr, true);
  WritePcd(dir + "/binary_labels.pcd", plain, &labels, true);
  WritePcd(dir + "/ascii_labels.pcd", plain, &labels, false);
  WritePcd(dir + "/empty_cloud.pcd", Cloud{}, nullptr, false);
  // Other writers: comments, CRLF, types of every size, a skipped multi-count field, WIDTH x
  // HEIGHT organised, signs, exponents.
  Text(dir + "/other_writer.pcd",
       "# .PCD v0.7\r\nVERSION .7\r\nFIELDS x y z rgb normal intensity ring\r\n"
       "SIZE 8 4 4 4 4 2 1\r\nTYPE F F F U F U U\r\nCOUNT 1 1 1 1 3 1 1\r\nWIDTH 2\r\n"
       "HEIGHT 2\r\nVIEWPOINT 0 0 0 1 0 0 0\r\nPOINTS 4\r\nDATA ascii\r\n"
       "1.5 -2 +3e-1 4294967295 0 0 1 65535 63\r\n-0 1e2 .5 0 nan inf -inf 0 0\r\n"
       "\r\n2 2 2 7 1 1 1 10 1\r\n3 3 3 7 1 1 1 10 2\r\n");
  Text(dir + "/no_intensity.pcd",
       "VERSION 0.7\nFIELDS z y x\nSIZE 2 8 1\nTYPE I F I\nWIDTH 2\nDATA ascii\n-5 0.25 -128\n"
       "32767 -1e300 127\n");
  Text(dir + "/compressed.pcd",
       Raw("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\n"
           "POINTS 1\nDATA binary_compressed\n\x0c\0\0\0\x0c\0\0\0"));
}

void Ply(const std::string& dir) {
  const Cloud ring = Points(true), plain = Points(false);
  const Labels labels = {1, 0, 0, 1, 0, 1};
  WritePly(dir + "/ascii_ring.ply", ring, nullptr, false);
  WritePly(dir + "/binary_ring.ply", ring, nullptr, true);
  WritePly(dir + "/binary_labels.ply", plain, &labels, true);
  WritePly(dir + "/empty_cloud.ply", Cloud{}, nullptr, true);
  // Other writers: obj_info, sized type names, scalar_intensity, a face element after the
  // vertices, CRLF.
  Text(dir + "/other_writer.ply",
       "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info scanner\r\n"
       "element vertex 3\r\nproperty double x\r\nproperty float32 y\r\nproperty int16 z\r\n"
       "property uint8 scalar_intensity\r\nproperty ushort ring\r\nelement face 1\r\n"
       "property list uchar int vertex_indices\r\nend_header\r\n1.5 2 -3 255 0\r\n"
       "-1e-3 inf 32767 0 65535\r\n0 0 0 7 3\r\n3 0 1 2\r\n");
  Text(dir + "/big_endian.ply",
       Raw("ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\n"
           "property float y\nproperty float z\nend_header\n\0\0\0\0\0\0\0\0\0\0\0\0"));
}

void SensorProfiles(const std::string& dir) {
  SensorProfile small;
  small.name = "small";
  small.beams = 16;
  small.width = 256;
  for (unsigned b = 0; b < small.beams; ++b) small.elevation_deg.push_back(2.0f - float(b));
  small.sensor_height = 1.7f;
  small.min_range = 1.0f;
  small.max_range = 100.0f;
  small.overrides = {{"sectors_near", 64}, {"sectors_far", 32}, {"grow_dz", 0.025f}};
  WriteSensorProfile(dir + "/written.txt", small);
  // What `lpir-gseg calibrate` writes: a profile with the mount tilt and fitted heights.
  SensorProfile calibrated = small;
  calibrated.name = "calibrated";
  calibrated.overrides.clear();
  calibrated.beam_origin_z.assign(small.beams, 0.125f);
  calibrated.ring_zero_is_top = true;
  calibrated.k_xz = 0.0123f;
  calibrated.k_yz = -0.00456f;
  calibrated.b_x = 1.734f;
  calibrated.b_y = 1.729f;
  WriteSensorProfile(dir + "/calibration.txt", calibrated);
  // The extremes the reader accepts (tilt 45 degrees, 1000 m) and a scale that makes any
  // intensity huge: every stage must still be defined (issue 6 found overflows with both).
  SensorProfile extreme = small;
  extreme.name = "extreme";
  extreme.overrides.clear();
  extreme.intensity_scale = 1e30f;
  extreme.k_xz = 1.0f;
  extreme.k_yz = -1.0f;
  extreme.max_range = 1000.0f;
  WriteSensorProfile(dir + "/extreme.txt", extreme);
  // By hand: comments, tabs, continuation lines after a comment, signs, exponents.
  Text(dir + "/by_hand.txt",
       "# a hand-made profile\nname\thand   # trailing comment\nbeams 4\nwidth 64\n"
       "elevation_deg +2.5 1e0\n# between the lines\n\n  -.5 -9.0e+1\nring_zero_is_top 1\n"
       "intensity_scale 0.00392156863\nsensor_height 1.73\nmin_range 0\nmax_range 1e3\n"
       "param rings_near 4\nparam min_component 0\nparam h_noise -3\n");
}

}  // namespace
}  // namespace lpir

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1];
  const struct {
    const char* target;
    void (*write)(const std::string&);
  } kTargets[] = {{"kitti_bin", lpir::KittiBin},
                  {"label_file", lpir::LabelFile},
                  {"pcd", lpir::Pcd},
                  {"ply", lpir::Ply},
                  {"sensor_profile", lpir::SensorProfiles}};
  try {
    for (const auto& t : kTargets) {
      const std::string dir = out + "/" + t.target;
      fs::remove_all(dir);
      fs::create_directories(dir);
      t.write(dir);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_corpus: %s\n", e.what());
    return 1;
  }
  return 0;
}
