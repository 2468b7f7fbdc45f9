// Fuzz target of the PLY reader (host/io/ply.h): any bytes either read as a well-formed cloud
// that survives a write/read round trip through WritePly (binary and ASCII), or throw IoError.
// Any other exception, a sanitizer report, a leak or a failed check is a finding.
#include <cstddef>
#include <cstdint>

#include "fuzz/cloud_checks.h"
#include "fuzz/fuzz_file.h"
#include "host/io/io_error.h"
#include "host/io/ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lpir;
  static fuzz::FuzzFile in, out;
  in.Write(data, size);
  Cloud cloud;
  try {
    cloud = ReadPly(in.path());
  } catch (const IoError&) {
    return 0;
  }
  fuzz::CheckCloudShape(cloud);
  fuzz::CheckRoundTrip(cloud, &out, WritePly, ReadPly);
  return 0;
}
