// PCD v0.7, DATA ascii, binary or binary_compressed (PCL's LZF): x y z required; the intensity
// under any of the names of IntensityNames() (0 when absent); ring optional; other fields
// skipped. Field types F/U/I of sizes 1/2/4/8, COUNT 1 for the fields read.
#pragma once
#include <string>

#include "reference_cpu/cloud.h"

namespace lpir {

// IoError naming the file and the problem: bad header, missing x/y/z, unknown DATA or type,
// POINTS/WIDTH*HEIGHT mismatch, fewer points than the header says, bytes after the data other
// than zeros (PCL 1.13 pads its files with them), compressed data whose sizes disagree with the
// header or the file or that does not decode. `note` (when given): NoIntensityNote's sentence
// when the file has no intensity field, else empty.
Cloud ReadPcd(const std::string& path, std::string* note = nullptr);
// labels may be null; binary selects DATA binary (else ascii).
void WritePcd(const std::string& path, const Cloud& cloud, const Labels* labels, bool binary);

}  // namespace lpir
