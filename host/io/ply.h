// PLY, format ascii 1.0 or binary_little_endian 1.0, element vertex with scalar properties
// x y z, the intensity under any of the names of IntensityNames() (0 when absent), optional ring;
// other properties skipped.
#pragma once
#include <string>

#include "reference_cpu/cloud.h"

namespace lpir {

// IoError naming the file and the problem: not PLY, big-endian, unsupported property type (named),
// list property in vertex, missing x/y/z, fewer vertices than the header says. `note` (when
// given): NoIntensityNote's sentence when the vertices have no intensity property, else empty.
Cloud ReadPly(const std::string& path, std::string* note = nullptr);
void WritePly(const std::string& path, const Cloud& cloud, const Labels* labels, bool binary);

}  // namespace lpir
