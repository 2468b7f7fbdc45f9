// The sensor profile a command line asks for: --sensor (a name or a profile file) with every
// --set NAME=VALUE applied in order (host/io/sensor_profile.h, ApplySettings).
#pragma once
#include <string>

#include "apps/cli/args.h"
#include "reference_cpu/sensor.h"

namespace lpir {

// The help text's lines for --set, for every command that takes it (a macro, so that it joins
// the string literals of a help text).
#define LPIR_SET_HELP                                                                            \
  "  --set NAME=VALUE change one setting of the profile for this run, as a line `NAME VALUE`\n"  \
  "                   or `param NAME VALUE` in the profile would (repeatable): sensor_height,\n" \
  "                   min_range, max_range, k_xz, k_yz, ring_zero_is_top, max_points, mount\n"   \
  "                   (fixed or per_frame), or a parameter of reference_cpu/params.cpp\n"        \
  "                   (--set h_athr=0.15)\n"

// Profile `name` (LoadSensorProfile in SensorsDir()) with args' --set values applied.
// std::invalid_argument for an unknown profile, a --set without '=', an unknown setting (naming
// the nearest) or a bad value; IoError for a profile file that does not parse.
SensorProfile LoadProfileWithSettings(const std::string& name, const Args& args);

}  // namespace lpir
