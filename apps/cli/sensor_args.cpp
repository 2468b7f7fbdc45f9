#include "apps/cli/sensor_args.h"

#include <stdexcept>
#include <utility>
#include <vector>

#include "apps/cli/commands.h"
#include "host/io/sensor_profile.h"

namespace lpir {

SensorProfile LoadProfileWithSettings(const std::string& name, const Args& args) {
  std::vector<std::pair<std::string, std::string>> settings;
  for (const std::string& s : args.GetAll("--set")) {
    const size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::invalid_argument("--set expects NAME=VALUE (--set sensor_height=1.9), not '" + s +
                                  "'");
    settings.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  SensorProfile profile = LoadSensorProfile(name, SensorsDir());
  try {
    ApplySettings(profile, settings);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--set ") + e.what());
  }
  return profile;
}

}  // namespace lpir
