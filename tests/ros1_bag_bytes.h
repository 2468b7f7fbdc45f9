// Builders of ROS 1 bag 2.0 bytes, record by record, for the tests and the fuzz corpus that write
// bags by hand (the reader is host/drive/ros1_bag_reader.cpp): little-endian integers, a header
// field "name=value" with its length, a record (header length, header, data length, data), the op
// field, and bzip2 compression as rosbag writes chunks (block size 9).
#pragma once
#include <bzlib.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace lpir::bag_bytes {

inline std::string U32(uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }
inline std::string U64(uint64_t v) { return std::string(reinterpret_cast<const char*>(&v), 8); }
inline std::string Field(const std::string& name, const std::string& value) {
  return U32(uint32_t(name.size() + 1 + value.size())) + name + "=" + value;
}
inline std::string Record(const std::string& header, const std::string& data) {
  return U32(uint32_t(header.size())) + header + U32(uint32_t(data.size())) + data;
}
inline std::string Op(uint8_t op) { return Field("op", std::string(1, char(op))); }

// std::runtime_error when libbz2 fails.
inline std::string Bz2(const std::string& in) {
  std::vector<char> out(in.size() + in.size() / 100 + 600);
  unsigned n = unsigned(out.size());
  if (BZ2_bzBuffToBuffCompress(out.data(), &n, const_cast<char*>(in.data()), unsigned(in.size()), 9,
                               0, 30) != BZ_OK)
    throw std::runtime_error("bz2 compression failed");
  return std::string(out.data(), n);
}

}  // namespace lpir::bag_bytes
