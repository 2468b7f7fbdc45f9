// Fuzz target of the PCD reader (host/io/pcd.h; DATA ascii, binary and binary_compressed with its
// LZF stream, host/io/lzf.h): any bytes either read as a well-formed cloud that survives a
// write/read round trip through WritePcd (binary and ASCII), or throw IoError.
// Any other exception, a sanitizer report, a leak or a failed check is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz/cloud_checks.h"
#include "host/io/pcd.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return lpir::fuzz::FuzzCloudFormat(data, size, lpir::ReadPcd, lpir::WritePcd);
}
