// Sensor profiles: small text files in sensors/ (see sensors/README.md for the format).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "reference_cpu/sensor.h"

namespace lpir {

// The profiles' folder: $LPIR_SENSORS_DIR when set and not empty, else the folder this library was
// built for: sensors/ of the source tree for the build tree's libraries, <prefix>/share/lpir_gseg/
// sensors for the installed one (the CMAKE_INSTALL_PREFIX it was configured with).
std::string DefaultSensorsDir();

// `name_or_path` is a profile name (sensors_dir/<name>.txt) or a path to a profile file.
// std::invalid_argument listing the known names (and the nearest one) for a name that is none;
// IoError (errno ENOENT) for a path, holding a '/', to a file that does not exist; IoError naming
// the file and line for a malformed profile (unknown key, unknown parameter override, bad number,
// elevation table not matching `beams` or not descending, ...).
SensorProfile LoadSensorProfile(const std::string& name_or_path,
                                const std::string& sensors_dir = DefaultSensorsDir());
// Names of the profiles in sensors_dir (file stems), sorted.
std::vector<std::string> KnownSensorProfiles(const std::string& sensors_dir = DefaultSensorsDir());
// The names ApplySettings takes: the profile keys that tune the segmentation of a sensor
// (sensor_height, min_range, max_range, k_xz, k_yz, ring_zero_is_top, max_points, mount), then
// every parameter (ParamNames()).
std::vector<std::string> SettingNames();
// Applies each NAME=VALUE in order, as the profile line `NAME VALUE` (a key) or `param NAME VALUE`
// (a parameter) would, with the reader's checks of the value; a later one replaces an earlier one
// of the same name. Then checks the profile as a whole (max_range above min_range, the grid and
// parameter rules of ParamsForSensor). std::invalid_argument "NAME=VALUE: problem" for an
// unknown name (with the nearest known one) or a bad value; "A=1, B=2: problem" for a whole
// that does not hold. `profile` may be half-changed when it throws.
void ApplySettings(SensorProfile& profile,
                   const std::vector<std::pair<std::string, std::string>>& settings);
// The profile file's words for the enumerated keys: "spinning", "rosette", "band"; "fixed",
// "per_frame".
const char* PatternName(ScanPattern pattern);
const char* MountName(MountSource mount);
// Writes a profile that LoadSensorProfile reads back identically.
void WriteSensorProfile(const std::string& path, const SensorProfile& profile);

}  // namespace lpir
