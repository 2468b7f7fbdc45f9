// DefaultSensorsDir (host/io/sensor_profile.h). kBuiltSensorsDir is the profiles' folder of the
// copy of the library this object is linked into, defined in a one-line source that
// host/io/CMakeLists.txt writes for each copy: the source tree's sensors/ for the build tree's
// libraries, the installed profiles for the installed archive.
#include <cstdlib>
#include <string>

#include "host/io/sensor_profile.h"

namespace lpir {

extern const char kBuiltSensorsDir[];

std::string DefaultSensorsDir() {
  const char* env = std::getenv("LPIR_SENSORS_DIR");
  return env && *env ? env : kBuiltSensorsDir;
}

}  // namespace lpir
