// The committed cloud-file fixtures (tests/data/clouds/, written by PCL and CloudCompare:
// tools/cloud_fixtures/make_cloud_fixtures.sh).
#pragma once
#include <string>

#include "tests/test_util.h"

namespace lpir::test {

// tests/data/clouds/<name>, or $LPIR_TEST_DATA_DIR/clouds/<name>.
inline std::string CloudFixture(const std::string& name) {
  return EnvOr("LPIR_TEST_DATA_DIR", LPIR_TEST_DATA_DIR) + std::string("/clouds/") + name;
}

}  // namespace lpir::test
