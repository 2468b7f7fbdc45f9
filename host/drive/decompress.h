// The chunk compressions of MCAP (zstd, lz4) and ROS 1 bags (bz2, lz4), from Debian's libzstd,
// liblz4 and libbz2. Each returns exactly `expected_size` bytes (the size the container records)
// or throws IoError naming `where` with the library's reason (corrupt data, wrong size).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lpir {

std::vector<uint8_t> DecompressZstd(const std::string& where, const uint8_t* data, size_t size,
                                    size_t expected_size);
// The LZ4 frame format (magic 0x184D2204), which both MCAP and ROS 1's roslz4 write.
std::vector<uint8_t> DecompressLz4Frame(const std::string& where, const uint8_t* data, size_t size,
                                        size_t expected_size);
std::vector<uint8_t> DecompressBz2(const std::string& where, const uint8_t* data, size_t size,
                                   size_t expected_size);

// Compressors for the writers (MCAP and ROS 1 bag chunks) and for tests. The LZ4 frame is the one
// ROS 1's roslz4 reads (it refuses others): independent blocks, a content checksum, no content
// size; MCAP readers read it too.
std::vector<uint8_t> CompressZstd(const uint8_t* data, size_t size);
std::vector<uint8_t> CompressLz4Frame(const uint8_t* data, size_t size);

// CRC-32 (ISO-HDLC, as MCAP uses), continuing from `crc` (0 to start): zlib's, which reads
// several bytes a step.
uint32_t Crc32(const uint8_t* data, size_t size, uint32_t crc = 0);

}  // namespace lpir
