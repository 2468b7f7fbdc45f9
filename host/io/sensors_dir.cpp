// DefaultSensorsDir (host/io/sensor_profile.h). LPIR_SENSORS_DIR is the folder of the library this
// object goes into: CMakeLists.txt compiles this file once for the build tree's libraries and once
// for the installed one.
#include <cstdlib>
#include <string>

#include "host/io/sensor_profile.h"

#ifndef LPIR_SENSORS_DIR
#error "LPIR_SENSORS_DIR must name the sensor profiles' folder (CMakeLists.txt defines it)"
#endif

namespace lpir {

std::string DefaultSensorsDir() {
  const char* env = std::getenv("LPIR_SENSORS_DIR");
  return env && *env ? env : LPIR_SENSORS_DIR;
}

}  // namespace lpir
