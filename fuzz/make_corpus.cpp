// Writes the seed corpus of every fuzz target: small valid files from the project's own writers
// and hand-made edge cases (comments, CRLF, skipped and multi-count fields, NaN/Inf, 0 points,
// PCD binary_compressed with LZF references, other elements, continuation lines, calibration
// keys; PointCloud2 layouts of every kind; small .db3 bags of each rosbag2 schema; MCAP drives
// from the writer and by hand; ROS 1 bags indexed or not, of each chunk compression, truncated),
// one folder per target.
// Usage: make_corpus OUT_DIR  (fuzz/corpus/ holds its output, checked by ctest: fuzz.corpus).
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/drive/decompress.h"
#include "host/drive/mcap_records.h"
#include "host/drive/mcap_writer.h"
#include "host/drive/pointcloud2.h"
#include "host/drive/ros1_bag_writer.h"
#include "host/io/file_bytes.h"
#include "host/io/io_error.h"
#include "host/io/kitti_bin.h"
#include "host/io/label_file.h"
#include "host/io/pcd.h"
#include "host/io/ply.h"
#include "host/io/sensor_profile.h"
#include "tests/ros1_bag_bytes.h"

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

template <typename T>
void Append(std::string* out, T value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

// `bytes` as LZF (host/io/lzf.h): at each byte the longest earlier match of 3 to 264 bytes at
// most 8192 back (found by trying every start), else a literal; literals in runs of up to 32.
std::string Lzf(const std::string& bytes) {
  std::string out, literal;
  const auto flush = [&] {
    if (literal.empty()) return;
    out += char(literal.size() - 1);
    out += literal;
    literal.clear();
  };
  size_t i = 0;
  while (i < bytes.size()) {
    size_t best = 0, distance = 0;
    for (size_t from = i > 8192 ? i - 8192 : 0; from < i; ++from) {
      size_t n = 0;
      while (n < 264 && i + n < bytes.size() && bytes[from + n] == bytes[i + n]) ++n;
      if (n > best) {
        best = n;
        distance = i - from;
      }
    }
    if (best < 3) {
      literal += bytes[i++];
      if (literal.size() == 32) flush();
      continue;
    }
    flush();
    const size_t length = best - 2, back = distance - 1;
    out += char(std::min<size_t>(length, 7) << 5 | back >> 8);
    if (length >= 7) out += char(length - 7);
    out += char(back & 0xff);
    i += best;
  }
  flush();
  return out;
}

// What follows DATA binary_compressed: the compressed and decompressed sizes, then the LZF.
std::string CompressedBody(const std::string& fields) {
  const std::string stream = Lzf(fields);
  std::string body;
  Append(&body, uint32_t(stream.size()));
  Append(&body, uint32_t(fields.size()));
  return body + stream;
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
  // DATA binary_compressed as PCL writes it: the fields one after another (padding "_" not
  // stored), LZF with runs and references; then a multi-count field, an organised cloud and the
  // zero bytes PCL 1.13 leaves after the data.
  std::string soa;
  for (int k = 0; k < 4; ++k) {
    for (size_t i = 0; i < ring.size(); ++i) Append(&soa, ring.xyzi[4 * i + k]);
  }
  for (int32_t r : ring.ring) Append(&soa, r);
  Text(dir + "/compressed.pcd",
       "VERSION 0.7\nFIELDS x y z intensity ring _\nSIZE 4 4 4 4 4 1\nTYPE F F F F I U\n"
       "COUNT 1 1 1 1 1 3\nWIDTH 6\nHEIGHT 1\nPOINTS 6\nDATA binary_compressed\n" +
           CompressedBody(soa));
  soa.clear();
  for (int i = 0; i < 8; ++i) Append(&soa, double(i % 3) * 0.5);
  for (int i = 0; i < 8; ++i) Append(&soa, float(-i));
  for (int i = 0; i < 8; ++i) Append(&soa, uint16_t(1000));
  for (int i = 0; i < 8 * 3; ++i) Append(&soa, i % 3 == 2 ? 1.0f : 0.0f);
  Text(dir + "/compressed_organised.pcd",
       "VERSION 0.7\nFIELDS x y z normal\nSIZE 8 4 2 4\nTYPE F F U F\nCOUNT 1 1 1 3\nWIDTH 4\n"
       "HEIGHT 2\nPOINTS 8\nDATA binary_compressed\n" +
           CompressedBody(soa) + std::string(40, '\0'));
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

// metadata.yaml as rosbag2 writes it through yaml-cpp (Jazzy), as PyYAML dumps it (Humble: keys
// sorted, sequences not indented, a long string folded over lines), and the rest of the subset.
void BagMetadatas(const std::string& dir) {
  Text(dir + "/rosbag2_jazzy.yaml",
       "rosbag2_bagfile_information:\n  version: 9\n  storage_identifier: mcap\n"
       "  duration:\n    nanoseconds: 200000000\n  starting_time:\n"
       "    nanoseconds_since_epoch: 1600000000000000000\n  message_count: 3\n"
       "  topics_with_message_count:\n    - topic_metadata:\n        name: /points\n"
       "        type: sensor_msgs/msg/PointCloud2\n        serialization_format: cdr\n"
       "        offered_qos_profiles:\n          - history: keep_last\n            depth: 5\n"
       "            deadline:\n              sec: 9223372036\n              nsec: 854775807\n"
       "        type_description_hash: RIHS01_00\n      message_count: 3\n"
       "  compression_format: \"\"\n  compression_mode: \"\"\n  relative_file_paths:\n"
       "    - run_0.mcap\n    - run_1.mcap\n  files:\n    - path: run_0.mcap\n"
       "      message_count: 2\n  custom_data: ~\n  ros_distro: jazzy\n");
  Text(dir + "/pyyaml_humble.yaml",
       "rosbag2_bagfile_information:\n  compression_format: ''\n  compression_mode: ''\n"
       "  message_count: 3\n  relative_file_paths:\n  - run_0.db3\n  - run_1.db3\n"
       "  storage_identifier: sqlite3\n  topics_with_message_count:\n  - message_count: 3\n"
       "    topic_metadata:\n      name: /points\n"
       "      offered_qos_profiles: \"- history: 3\\n  depth: 0\\n  durability:\\\n"
       "        \\ 2\\n  avoid_ros_namespace_conventions: false\\n\"\n"
       "      serialization_format: cdr\n      type: sensor_msgs/msg/PointCloud2\n"
       "  version: 5\n");
  Text(dir + "/subset.yaml",
       "---\n# comment\nrosbag2_bagfile_information:\n  relative_file_paths: ['a_0.mcap', b]\n"
       "  note: |\n    literal\n     kept\n  folded: >-\n    one\n    two\n"
       "  quoted: 'it''s'\n  escapes: \"\\t\\u00e9\\x41\"\n  empty: {}\n  none: []\n"
       "  plain: several\n    lines\n");
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
  // The extremes the reader accepts (tilt 45 degrees, 1000 m): every stage must still be defined.
  SensorProfile extreme = small;
  extreme.name = "extreme";
  extreme.overrides.clear();
  extreme.k_xz = 1.0f;
  extreme.k_yz = -1.0f;
  extreme.max_range = 1000.0f;
  WriteSensorProfile(dir + "/extreme.txt", extreme);
  // By hand: comments, tabs, continuation lines after a comment, signs, exponents.
  Text(dir + "/by_hand.txt",
       "# a hand-made profile\nname\thand   # trailing comment\nbeams 4\nwidth 64\n"
       "elevation_deg +2.5 1e0\n# between the lines\n\n  -.5 -9.0e+1\nring_zero_is_top 1\n"
       "sensor_height 1.73\nmin_range 0\nmax_range 1e3\n"
       "param rings_near 4\nparam min_component 0\nparam h_noise -3\n");
}

// A PointCloud2 of `points` with the given fields (offsets packed in order, `pad` bytes after
// each row), each field's value from the point by its name (x, y, z, ring, t the point's index,
// any other the intensity), cast to its type (which must hold it).
PointCloud2 Message(const Cloud& points, const std::vector<std::pair<std::string, uint8_t>>& specs,
                    uint32_t height, uint32_t pad, bool big) {
  PointCloud2 msg;
  msg.stamp_sec = 1700000000;
  msg.stamp_nanosec = 5;
  msg.frame_id = "lidar";
  msg.height = height;
  msg.width = uint32_t(points.size()) / height;
  msg.is_bigendian = big;
  const auto size = [](uint8_t t) { return t <= 2 ? 1u : t <= 4 ? 2u : t == 8 ? 8u : 4u; };
  for (const auto& [name, type] : specs) {
    msg.fields.push_back(PointField{name, msg.point_step, type, 1});
    msg.point_step += size(type);
  }
  msg.row_step = msg.width * msg.point_step + pad;
  msg.data.assign(size_t(msg.row_step) * height, 0);
  for (size_t p = 0; p < size_t(msg.width) * height; ++p) {
    uint8_t* record =
        msg.data.data() + (p / msg.width) * msg.row_step + (p % msg.width) * msg.point_step;
    for (size_t f = 0; f < specs.size(); ++f) {
      const std::string& name = specs[f].first;
      const double v = name == "x"      ? points.x(p)
                       : name == "y"    ? points.y(p)
                       : name == "z"    ? points.z(p)
                       : name == "ring" ? (points.ring.empty() ? 0.0 : points.ring[p])
                       : name == "t"    ? double(p)
                                        : points.intensity(p);  // intensity, reflectivity, i
      const double value = std::isfinite(v) || specs[f].second >= kPfFloat32 ? v : 0.0;
      uint8_t b[8] = {};
      switch (specs[f].second) {
        case kPfInt8: {
          const int8_t x = int8_t(value);
          std::memcpy(b, &x, 1);
          break;
        }
        case kPfUint8: {
          const uint8_t x = uint8_t(value);
          std::memcpy(b, &x, 1);
          break;
        }
        case kPfInt16: {
          const int16_t x = int16_t(value);
          std::memcpy(b, &x, 2);
          break;
        }
        case kPfUint16: {
          const uint16_t x = uint16_t(value);
          std::memcpy(b, &x, 2);
          break;
        }
        case kPfInt32: {
          const int32_t x = int32_t(value);
          std::memcpy(b, &x, 4);
          break;
        }
        case kPfUint32: {
          const uint32_t x = uint32_t(value);
          std::memcpy(b, &x, 4);
          break;
        }
        case kPfFloat32: {
          const float x = float(value);
          std::memcpy(b, &x, 4);
          break;
        }
        default:
          std::memcpy(b, &value, 8);
      }
      const size_t n = size(specs[f].second);
      for (size_t k = 0; k < n; ++k) record[msg.fields[f].offset + k] = big ? b[n - 1 - k] : b[k];
    }
  }
  return msg;
}

// Finite points with whole, small rings (every integer type holds them).
Cloud FinitePoints() {
  Cloud c;
  c.Push(5.25f, -1.5f, -1.73f, 25.0f);
  c.Push(-3.0f, 7.125f, 0.5f, 75.0f);
  c.Push(10.0f, 1.0f, -1.7f, 0.0f);
  c.Push(0.0f, 0.0f, 0.0f, 100.0f);
  c.ring = {0, 5, 15, 1};
  return c;
}

void Bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  WriteFileBytes(path, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void PointCloud2s(const std::string& dir) {
  const std::vector<std::pair<std::string, uint8_t>> ouster = {{"x", kPfFloat32},
                                                               {"y", kPfFloat32},
                                                               {"z", kPfFloat32},
                                                               {"intensity", kPfFloat32},
                                                               {"ring", kPfUint16}};
  Bytes(dir + "/float32_ring.cdr",
        SerializeCdrPointCloud2(Message(Points(false), ouster, 1, 0, false)));
  Bytes(dir + "/float64_big_endian.cdr",
        SerializeCdrPointCloud2(Message(FinitePoints(),
                                        {{"x", kPfFloat64},
                                         {"y", kPfFloat64},
                                         {"z", kPfFloat64},
                                         {"reflectivity", kPfUint16},
                                         {"ring", kPfUint8}},
                                        1, 0, true)));
  Bytes(dir + "/organised_padded.cdr", SerializeCdrPointCloud2(Message(FinitePoints(),
                                                                       {{"z", kPfFloat32},
                                                                        {"t", kPfUint32},
                                                                        {"x", kPfFloat32},
                                                                        {"y", kPfFloat32},
                                                                        {"i", kPfInt8},
                                                                        {"ring", kPfFloat32}},
                                                                       2, 3, false)));
  const PointCloud2 plain = Message(FinitePoints(), ouster, 1, 0, false);
  Bytes(dir + "/labelled.cdr",
        SerializeCdrPointCloud2(SplitByLabel(dir, plain, Labels{1, 0, 1, 0}).labelled));
  PointCloud2 empty = plain;
  empty.width = 0;
  empty.row_step = 0;
  empty.data.clear();
  Bytes(dir + "/empty.cdr", SerializeCdrPointCloud2(empty));
}

// A small bag (512-byte pages) in rosbag2's sqlite3 schema: `dashing` without
// offered_qos_profiles, else Humble's; a cdr PointCloud2 topic and a topic of another format.
void Db3(const std::string& path, bool dashing) {
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) throw IoError(path, "cannot create");
  const auto exec = [&](const std::string& sql) {
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) {
      const std::string error = sqlite3_errmsg(db);
      sqlite3_close(db);
      throw IoError(path, error);
    }
  };
  exec("PRAGMA page_size = 512");
  exec(std::string("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT "
                   "NULL, serialization_format TEXT NOT NULL") +
       (dashing ? ")" : ", offered_qos_profiles TEXT NOT NULL)"));
  exec(
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp "
      "INTEGER NOT NULL, data BLOB NOT NULL)");
  exec("CREATE INDEX timestamp_idx ON messages (timestamp ASC)");
  const std::string qos = dashing ? "" : ", ''";
  exec("INSERT INTO topics VALUES (1, '/points', 'sensor_msgs/msg/PointCloud2', 'cdr'" + qos + ")");
  exec("INSERT INTO topics VALUES (2, '/other', 'std_msgs/msg/String', 'json'" + qos + ")");
  const std::vector<std::pair<std::string, uint8_t>> fields = {
      {"x", kPfFloat32}, {"y", kPfFloat32}, {"z", kPfFloat32}, {"intensity", kPfUint8}};
  for (int i = 0; i < 3; ++i) {
    const std::vector<uint8_t> bytes =
        SerializeCdrPointCloud2(Message(FinitePoints(), fields, 1, 0, false));
    sqlite3_stmt* stmt = nullptr;
    sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?1, ?2, ?3)",
                       -1, &stmt, nullptr);
    sqlite3_bind_int(stmt, 1, i == 1 ? 2 : 1);
    sqlite3_bind_int64(stmt, 2, 1700000000000000000 + (2 - i) * 100000000);
    sqlite3_bind_blob(stmt, 3, bytes.data(), int(bytes.size()), SQLITE_TRANSIENT);
    const int rc = sqlite3_step(stmt);
    sqlite3_finalize(stmt);
    if (rc != SQLITE_DONE) {
      sqlite3_close(db);
      throw IoError(path, "cannot insert a message");
    }
  }
  sqlite3_close(db);
}

void Db3s(const std::string& dir) {
  Db3(dir + "/humble.db3", false);
  Db3(dir + "/dashing.db3", true);
}

// MCAP from the writer (each compression, two channels, a message larger than the rest) and by
// hand: no summary, messages in and outside chunks, zstd/lz4/unknown compression, an unknown
// opcode, a ros1 and a json channel, a CRC left unset.
void WriteMcapDrive(const std::string& path, McapCompression compression) {
  McapWriter w(path, compression);
  const uint16_t pc = w.AddSchema("sensor_msgs/msg/PointCloud2", "ros2msg", "uint8 x\n");
  const uint16_t points = w.AddChannel("/points", pc, "cdr");
  const uint16_t imu = w.AddChannel("/imu", 0, "cdr");
  for (uint32_t i = 0; i < 6; ++i) {
    std::vector<uint8_t> data(i == 3 ? 300 : 24, uint8_t(i));
    w.Write(points, i, 100 + 10 * uint64_t(5 - i), 1, data.data(), data.size());
    w.Write(imu, i, 100 + 10 * uint64_t(i), 1, data.data(), 8);
  }
  w.Close();
}

// Channel metadata, a metadata record and an attachment between the chunks (the whole-drive
// reader's records), profile ros1.
void WriteMcapRecords(const std::string& path) {
  McapWriter w(path, McapCompression::kZstd, "ros1");
  const uint16_t pc = w.AddSchema("sensor_msgs/PointCloud2", "ros1msg", "uint8 x\n");
  const uint16_t points = w.AddChannel("/points", pc, "ros1", {{"md5sum", "0"}, {"latching", "1"}});
  std::vector<uint8_t> data(24, 7);
  w.Write(points, 0, 100, 100, data.data(), data.size());
  w.AddMetadata(DriveMetadata{"drive_info", {{"vehicle", "a"}, {"route", "b"}}});
  w.AddAttachment(DriveAttachment{100, 0, "calib.yaml", "application/yaml", {'x', ':', '1'}});
  w.Write(points, 1, 200, 200, data.data(), data.size());
  w.Close();
}

void Mcap(const std::string& dir) {
  WriteMcapRecords(dir + "/records.mcap");
  WriteMcapDrive(dir + "/none.mcap", McapCompression::kNone);
  WriteMcapDrive(dir + "/zstd.mcap", McapCompression::kZstd);
  WriteMcapDrive(dir + "/lz4.mcap", McapCompression::kLz4);
  mcap::Out f;
  f.Raw(mcap::kMagic, mcap::kMagicSize);
  auto add = [&f](uint8_t op, const mcap::Out& content) { f.Record(op, content); };
  mcap::Out header, schema, ros1, json, loose, extension, data_end, footer;
  header.Str("ros1");
  header.Str("hand");
  add(mcap::kHeader, header);
  schema.U16(1);
  schema.Str("sensor_msgs/PointCloud2");
  schema.Str("ros1msg");
  schema.Str("");
  add(mcap::kSchema, schema);
  ros1.U16(1);
  ros1.U16(1);
  ros1.Str("/ros1");
  ros1.Str("ros1");
  ros1.U32(0);
  add(mcap::kChannel, ros1);
  json.U16(2);
  json.U16(0);
  json.Str("/json");
  json.Str("json");
  json.U32(0);
  add(mcap::kChannel, json);
  auto message = [](uint16_t channel, uint64_t time, const char* text) {
    mcap::Out m;
    m.U16(channel);
    m.U32(0);
    m.U64(time);
    m.U64(time);
    m.Raw(text, std::char_traits<char>::length(text));
    return m;
  };
  add(mcap::kMessage, message(1, 5, "loose"));
  extension.Raw("ext", 3);
  for (const char* compression : {"", "zstd", "lz4", "br"}) {
    mcap::Out records;
    records.Record(0x90, extension);
    records.Record(mcap::kMessage, message(1, 9, "second"));
    records.Record(mcap::kMessage, message(1, 7, "first"));
    records.Record(mcap::kMessage, message(2, 8, "{}"));
    std::vector<uint8_t> stored = records.bytes;
    const std::string c = compression;
    if (c == "zstd") stored = CompressZstd(records.bytes.data(), records.bytes.size());
    if (c == "lz4") stored = CompressLz4Frame(records.bytes.data(), records.bytes.size());
    mcap::Out chunk;
    chunk.U64(7);
    chunk.U64(9);
    chunk.U64(records.bytes.size());
    chunk.U32(c == "zstd" ? 0 : Crc32(records.bytes.data(), records.bytes.size()));
    chunk.Str(c);
    chunk.U64(stored.size());
    chunk.Raw(stored.data(), stored.size());
    add(mcap::kChunk, chunk);
  }
  add(0xA5, extension);
  data_end.U32(0);
  add(mcap::kDataEnd, data_end);
  footer.U64(0);
  footer.U64(0);
  footer.U32(0);
  add(mcap::kFooter, footer);
  f.Raw(mcap::kMagic, mcap::kMagicSize);
  WriteFileBytes(dir + "/by_hand.mcap", f.bytes.data(), f.bytes.size());
  // The same, cut inside its last chunk.
  WriteFileBytes(dir + "/cut.mcap", f.bytes.data(), f.bytes.size() - 60);
}

// --- ROS 1 bags (bag format 2.0), written record by record ---

// A PointCloud2 of two points (x, y, z float32, intensity uint8, ring uint16).
std::string Ros1Cloud(uint32_t seq) {
  PointCloud2 c;
  c.seq = seq;
  c.stamp_sec = int32_t(1700000000 + seq);
  c.stamp_nanosec = 5000;
  c.frame_id = "velodyne";
  c.width = 2;
  c.fields = {{"x", 0, kPfFloat32, 1},
              {"y", 4, kPfFloat32, 1},
              {"z", 8, kPfFloat32, 1},
              {"intensity", 12, kPfUint8, 1},
              {"ring", 13, kPfUint16, 1}};
  c.point_step = 15;
  c.row_step = 30;
  const float xyz[] = {5.25f, -1.5f, -1.73f, -3.0f, 7.125f, 0.5f};
  for (int p = 0; p < 2; ++p) {
    const auto* b = reinterpret_cast<const uint8_t*>(&xyz[3 * p]);
    c.data.insert(c.data.end(), b, b + 12);
    c.data.push_back(uint8_t(40 * p + seq));
    c.data.push_back(uint8_t(p + 1));
    c.data.push_back(0);
  }
  c.is_dense = true;
  const auto bytes = SerializeRos1PointCloud2(c);
  return std::string(bytes.begin(), bytes.end());
}

// Two chunks of /points (connections 0 and 3) and /imu (connection 1), each chunk followed by its
// index data; `indexed`: the connections and chunk infos at the end, the bag header pointing at
// them (else index_pos 0, as a recorder that died leaves it); `padded`: the bag header padded to
// 4096 bytes as rosbag writes it.
std::string Ros1Bag(const std::string& compression, bool indexed, bool padded) {
  const std::map<uint32_t, std::string> topics = {{0, "/points"}, {1, "/imu"}, {3, "/points"}};
  auto connection = [&](uint32_t id) {
    const std::string& topic = topics.at(id);
    const std::string type = topic == "/imu" ? "sensor_msgs/Imu" : "sensor_msgs/PointCloud2";
    return bag_bytes::Record(bag_bytes::Op(7) + bag_bytes::Field("conn", bag_bytes::U32(id)) +
                                 bag_bytes::Field("topic", topic),
                             bag_bytes::Field("topic", topic) + bag_bytes::Field("type", type) +
                                 bag_bytes::Field("md5sum", "1158d486dd51d683ce2f1be655c3c181") +
                                 bag_bytes::Field("message_definition", "Header header") +
                                 bag_bytes::Field("callerid", "/velodyne") +
                                 bag_bytes::Field("latching", "0"));
  };
  struct Msg {
    uint32_t conn, sec, nsec;
    std::string data;
  };
  const std::vector<std::vector<Msg>> chunks = {
      {{0, 10, 0, Ros1Cloud(0)}, {1, 10, 5, "imu"}, {3, 9, 7, Ros1Cloud(1)}},
      {{0, 11, 0, Ros1Cloud(2)}, {3, 11, 0, Ros1Cloud(3)}}};
  std::string body, infos;
  std::map<uint32_t, bool> written;
  const std::string magic = "#ROSBAG V2.0\n";
  auto header = [&](uint64_t index_pos) {
    const std::string h = bag_bytes::Op(3) +
                          bag_bytes::Field("index_pos", bag_bytes::U64(index_pos)) +
                          bag_bytes::Field("conn_count", bag_bytes::U32(indexed ? 3 : 0)) +
                          bag_bytes::Field("chunk_count", bag_bytes::U32(indexed ? 2 : 0));
    return bag_bytes::Record(h, padded ? std::string(4096 - 8 - h.size(), ' ') : "");
  };
  const size_t header_size = header(0).size();
  for (const auto& chunk : chunks) {
    std::string inner;
    std::map<uint32_t, std::string> index;
    std::map<uint32_t, uint32_t> counts;
    for (const Msg& m : chunk) {
      if (!written[m.conn]) inner += connection(m.conn);
      written[m.conn] = true;
      index[m.conn] +=
          bag_bytes::U32(m.sec) + bag_bytes::U32(m.nsec) + bag_bytes::U32(uint32_t(inner.size()));
      ++counts[m.conn];
      inner += bag_bytes::Record(
          bag_bytes::Op(2) + bag_bytes::Field("conn", bag_bytes::U32(m.conn)) +
              bag_bytes::Field("time", bag_bytes::U32(m.sec) + bag_bytes::U32(m.nsec)),
          m.data);
    }
    const std::string data = compression == "bz2"   ? bag_bytes::Bz2(inner)
                             : compression == "lz4" ? [&] {
                                 const auto v = CompressLz4Frame(
                                     reinterpret_cast<const uint8_t*>(inner.data()), inner.size());
                                 return std::string(v.begin(), v.end());
                               }()
                                                    : inner;
    const uint64_t chunk_pos = magic.size() + header_size + body.size();
    body += bag_bytes::Record(bag_bytes::Op(5) + bag_bytes::Field("compression", compression) +
                                  bag_bytes::Field("size", bag_bytes::U32(uint32_t(inner.size()))),
                              data);
    std::string info;
    for (const auto& [conn, entries] : index) {
      body += bag_bytes::Record(bag_bytes::Op(4) + bag_bytes::Field("ver", bag_bytes::U32(1)) +
                                    bag_bytes::Field("conn", bag_bytes::U32(conn)) +
                                    bag_bytes::Field("count", bag_bytes::U32(counts[conn])),
                                entries);
      info += bag_bytes::U32(conn) + bag_bytes::U32(counts[conn]);
    }
    infos += bag_bytes::Record(
        bag_bytes::Op(6) + bag_bytes::Field("ver", bag_bytes::U32(1)) +
            bag_bytes::Field("chunk_pos", bag_bytes::U64(chunk_pos)) +
            bag_bytes::Field("start_time", bag_bytes::U32(chunk.front().sec) + bag_bytes::U32(0)) +
            bag_bytes::Field("end_time", bag_bytes::U32(chunk.back().sec) + bag_bytes::U32(0)) +
            bag_bytes::Field("count", bag_bytes::U32(uint32_t(counts.size()))),
        info);
  }
  const uint64_t index_pos = magic.size() + header_size + body.size();
  std::string bag = magic + header(indexed ? index_pos : 0) + body;
  if (indexed) bag += connection(0) + connection(1) + connection(3) + infos;
  return bag;
}

// A bag from Ros1BagWriter: two connections (one latched), three messages.
void WrittenRos1Bag(const std::string& path) {
  Ros1BagWriter w(path);
  const uint32_t cloud = w.AddConnection(
      "/points",
      {{"type", "sensor_msgs/PointCloud2"}, {"md5sum", "0"}, {"message_definition", ""}});
  const uint32_t gps = w.AddConnection("/gps", {{"type", "std_msgs/String"},
                                                {"md5sum", "0"},
                                                {"message_definition", "string data\n"},
                                                {"latching", "1"}});
  const std::string cloud0 = Ros1Cloud(0), text = "\x02\0\0\0hi";
  w.Write(cloud, 1000000000, reinterpret_cast<const uint8_t*>(cloud0.data()), cloud0.size());
  w.Write(gps, 1000000001, reinterpret_cast<const uint8_t*>(text.data()), text.size());
  w.Write(cloud, 1100000000, reinterpret_cast<const uint8_t*>(cloud0.data()), cloud0.size());
  w.Close();
}

void Ros1Bags(const std::string& dir) {
  WrittenRos1Bag(dir + "/written.bag");
  for (const char* compression : {"none", "bz2", "lz4"})
    Text(dir + "/indexed_" + compression + ".bag", Ros1Bag(compression, true, true));
  Text(dir + "/unindexed_bz2.bag", Ros1Bag("bz2", false, true));
  Text(dir + "/unpadded_lz4.bag", Ros1Bag("lz4", true, false));
  Text(dir + "/unpadded_unindexed.bag", Ros1Bag("none", false, false));
  const std::string whole = Ros1Bag("none", true, false);
  // Cut inside the second chunk's data, and between the chunks and the index.
  Text(dir + "/truncated_mid_chunk.bag",
       whole.substr(0, whole.find("compression=", whole.find("compression=") + 1) + 120));
  uint64_t index_pos = 0;
  whole.copy(reinterpret_cast<char*>(&index_pos), 8, whole.find("index_pos=") + 10);
  Text(dir + "/truncated_before_index.bag", whole.substr(0, size_t(index_pos)));
  std::string unknown = Ros1Bag("lz4", true, false);
  unknown.replace(unknown.find("compression=lz4"), 15, "compression=zst");
  Text(dir + "/unknown_compression.bag", unknown);
  Text(dir + "/version_1_2.bag", "#ROSBAG V1.2\n");
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
  } kTargets[] = {{"bag_metadata", lpir::BagMetadatas},
                  {"db3", lpir::Db3s},
                  {"kitti_bin", lpir::KittiBin},
                  {"label_file", lpir::LabelFile},
                  {"mcap", lpir::Mcap},
                  {"pcd", lpir::Pcd},
                  {"ply", lpir::Ply},
                  {"pointcloud2", lpir::PointCloud2s},
                  {"ros1_bag", lpir::Ros1Bags},
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
