// The scenes every stage's Vulkan test runs (tests/<stage>_vk_test.cpp): simulated HDL-64E streets
// and the real scans in ../shared/data, each loaded with its sensor's profile and run through the
// whole reference (RunReference), as a value-parameterised fixture. A stage's test writes one
// TEST_P on StageScene's members and LPIR_STAGE_SCENES(its fixture).
#pragma once
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "apps/sim/scene.h"
#include "host/io/cloud_file.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/pipeline.h"
#include "tests/stage_test_util.h"
#include "tests/test_util.h"
#include "tests/vk_test_util.h"

namespace lpir::test {

struct SceneCase {
  const char* name;    // the test's name suffix
  const char* sensor;  // a profile in sensors/
  const char* file;    // a real scan under ../shared/data; nullptr: simulated with `sim`
  SimOptions sim;
};

// gtest prints a scene by its name (the test's name shows it, not the struct's bytes).
inline void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

inline SimOptions Street(uint32_t seed, SceneKind kind, float pitch_deg, bool rings) {
  SimOptions o;
  o.seed = seed, o.kind = kind, o.pitch_deg = pitch_deg, o.emit_rings = rings;
  return o;
}

// Simulated: urban streets (one pitched, two with rings), flat ground with objects, flat ground.
// Real: both KITTI dev scans, a nuScenes sweep with rings, RELLIS-3D's Ouster and Velodyne, and
// an HDL-32E .ply.
inline std::vector<SceneCase> StageScenes() {
  return {
      {"SimUrban1", "hdl64e", nullptr, Street(1, kUrban, 0.0f, false)},
      {"SimUrban2PitchedRings", "hdl64e", nullptr, Street(2, kUrban, 1.5f, true)},
      {"SimUrban4", "hdl64e", nullptr, Street(4, kUrban, 0.0f, false)},
      {"SimUrban13Rings", "hdl64e", nullptr, Street(13, kUrban, 0.0f, true)},
      {"SimFlatWithObjects", "hdl64e", nullptr, Street(0, kFlatWithObjects, 0.0f, false)},
      {"SimFlat", "hdl64e", nullptr, Street(0, kFlat, 0.0f, false)},
      {"Kitti07Frame964", "hdl64e", "kitti/07/velodyne/000964.bin", {}},
      {"KittiUnknownFrame56", "hdl64e", "kitti/unknown/velodyne/000056.bin", {}},
      {"NuScenesSweepWithRings",
       "hdl32e",
       "nuscenes/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin",
       {}},
      {"Rellis3dOuster", "os1-64", "rellis3d/os1/000104.bin", {}},
      {"Rellis3dVlp32c", "vlp32c", "rellis3d/vlp32c/000104.bin", {}},
      {"Hdl32ePly", "hdl32e", "hdl32e/source.ply", {}},
  };
}

// One scene, loaded (a real scan absent: the test skips), and the reference's frame of it.
class StageScene : public VkTest, public ::testing::WithParamInterface<SceneCase> {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    const SceneCase& c = GetParam();
    const SensorProfile s = LoadSensorProfile(c.sensor, SensorsDir());
    if (c.file) {
      LPIR_REQUIRE_DATA(c.file);
      cloud = ReadCloud(DataFile(c.file));
    } else {
      cloud = Simulate(s, c.sim).cloud;
    }
    p = ParamsForSensor(s);
    t = MakeTables(s, p);
    RunReference(cloud, p, t, frame);
    what = c.name;
  }

  Cloud cloud;
  Params p;
  Tables t;
  Frame frame;  // every buffer of the reference's run
  std::string what;
};

// The reference's frame of a random street (StreetWithSecondReturns) of base + per_seed * seed
// points for each seed, under `sensor`'s parameters.
struct RandomStreet {
  Cloud cloud;
  Params p;
  Frame frame;
  std::string what;
};
inline std::vector<RandomStreet> RandomStreets(const SensorProfile& sensor,
                                               const std::vector<uint32_t>& seeds, size_t base,
                                               size_t per_seed) {
  std::vector<RandomStreet> out;
  for (uint32_t seed : seeds) {
    RandomStreet s{StreetWithSecondReturns(base + per_seed * seed, sensor.sensor_height, seed),
                   ParamsForSensor(sensor),
                   {},
                   sensor.name + ", random street " + std::to_string(seed)};
    RunReference(s.cloud, s.p, MakeTables(sensor, s.p), s.frame);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace lpir::test

// Runs `fixture`'s TEST_Ps on every scene of StageScenes().
#define LPIR_STAGE_SCENES(fixture)                                                             \
  INSTANTIATE_TEST_SUITE_P(Scenes, fixture, ::testing::ValuesIn(::lpir::test::StageScenes()),  \
                           [](const ::testing::TestParamInfo<::lpir::test::SceneCase>& info) { \
                             return std::string(info.param.name);                              \
                           })
