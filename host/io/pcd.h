// PCD v0.7, DATA ascii or binary: x y z required; intensity optional (0 when absent); ring
// optional; other fields skipped. Field types F/U/I of sizes 1/2/4/8, COUNT 1.
#pragma once
#include <string>

#include "reference_cpu/cloud.h"

namespace lpir {

// IoError naming the file and the problem: bad header, missing x/y/z, unsupported DATA
// (binary_compressed) or type, POINTS/WIDTH*HEIGHT mismatch, fewer points than the header says.
Cloud ReadPcd(const std::string& path);
// labels may be null; binary selects DATA binary (else ascii).
void WritePcd(const std::string& path, const Cloud& cloud, const Labels* labels, bool binary);

}  // namespace lpir
