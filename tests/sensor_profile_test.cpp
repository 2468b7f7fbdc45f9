// Sensor profiles: every shipped profile loads and is consistent, write/read round-trips exactly,
// and every malformed file is rejected with an IoError naming the file and the line.
#include "host/io/sensor_profile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/io/io_error.h"
#include "reference_cpu/params.h"
#include "tests/test_util.h"

namespace lpir {
namespace {

const char* const kShipped[] = {"hdl32e", "hdl64e",   "mid360",    "mid70", "os1-128", "os1-64",
                                "ot128",  "pandar64", "rs-ruby80", "vlp16", "vlp32c"};

std::string WriteText(const std::string& dir, const std::string& name, const std::string& text) {
  std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

const char kValid[] =
    "# a valid profile\n"
    "name tiny\n"
    "beams 4\n"
    "width 1024\n"
    "elevation_deg 3.0 1.0   # the table continues\n"
    "  -1.0 -3.0\n"
    "ring_zero_is_top 1\n"
    "# intensity is not read: no key for it\n"
    "sensor_height 1.84\n"
    "min_range 2\n"
    "max_range 100\n"
    "param slope_max 0.06\n"
    "param min_component 30\n";

TEST(SensorProfile, EveryShippedProfileLoadsAndIsConsistent) {
  std::vector<std::string> known = KnownSensorProfiles(test::SensorsDir());
  EXPECT_EQ(known, std::vector<std::string>(std::begin(kShipped), std::end(kShipped)));
  for (const char* name : kShipped) {
    SCOPED_TRACE(name);
    SensorProfile p = LoadSensorProfile(name, test::SensorsDir());
    EXPECT_EQ(p.name, name);
    EXPECT_EQ(p.elevation_deg.size(), p.beams);
    EXPECT_EQ(p.width % 64, 0u);
    for (size_t i = 1; i < p.elevation_deg.size(); ++i)
      EXPECT_LT(p.elevation_deg[i], p.elevation_deg[i - 1]) << "beam " << i;
    EXPECT_GT(p.sensor_height, 0.0f);
    EXPECT_LT(p.min_range, p.max_range);
    // The pipeline accepts it: parameters and tables derive without complaint.
    Params params = ParamsForSensor(p);
    Tables tables = MakeTables(p, params);
    EXPECT_EQ(tables.beam_bound.size(), p.beams - 1);
  }
}

TEST(SensorProfile, ShippedGeometryMatchesTheDatasheets) {
  const std::string dir = test::SensorsDir();
  SensorProfile hdl64 = LoadSensorProfile("hdl64e", dir);
  ASSERT_EQ(hdl64.beams, 64u);
  EXPECT_NEAR(hdl64.elevation_deg.front(), 2.0, 0.3);   // datasheet: +2.0 ...
  EXPECT_NEAR(hdl64.elevation_deg.back(), -24.9, 0.3);  // ... to -24.9 degrees
  // Upper block (32 beams) ~1/3 degree apart, lower block ~1/2 degree.
  EXPECT_NEAR((hdl64.elevation_deg[0] - hdl64.elevation_deg[31]) / 31, 1.0 / 3, 0.03);
  EXPECT_NEAR((hdl64.elevation_deg[32] - hdl64.elevation_deg[63]) / 31, 0.5, 0.03);
  EXPECT_FLOAT_EQ(hdl64.sensor_height, 1.73f);
  EXPECT_FALSE(hdl64.ring_zero_is_top);

  SensorProfile hdl32 = LoadSensorProfile("hdl32e", dir);
  EXPECT_NEAR(hdl32.elevation_deg.front(), 10.67, 0.01);
  EXPECT_NEAR(hdl32.elevation_deg.back(), -30.67, 0.01);
  EXPECT_FALSE(hdl32.ring_zero_is_top);  // nuScenes: ring 0 is the bottom beam

  SensorProfile os1 = LoadSensorProfile("os1-64", dir);
  EXPECT_EQ(os1.width, 2048u);
  EXPECT_TRUE(os1.ring_zero_is_top);
  EXPECT_NEAR(os1.elevation_deg.front(), 16.6, 0.5);
  EXPECT_NEAR(os1.elevation_deg.back(), -16.6, 0.5);

  SensorProfile vlp32c = LoadSensorProfile("vlp32c", dir);
  EXPECT_FLOAT_EQ(vlp32c.elevation_deg.front(), 15.0f);
  EXPECT_FLOAT_EQ(vlp32c.elevation_deg.back(), -25.0f);

  EXPECT_EQ(LoadSensorProfile("os1-128", dir).beams, 128u);
  EXPECT_EQ(LoadSensorProfile("vlp16", dir).beams, 16u);
  for (const char* name : kShipped) {
    SensorProfile p = LoadSensorProfile(name, dir);
    const bool livox = std::string(name).rfind("mid", 0) == 0;
    EXPECT_EQ(p.pattern == ScanPattern::kSpinning, !livox) << name;
    EXPECT_EQ(p.mount == MountSource::kPerFrame, livox) << name;
  }
}

// Non-repetitive profiles: rows are 1 degree elevation bins over the datasheet's field of view,
// Mid-70 a 70.4 degree circle (+-35.2), Mid-360 -7 to +52 degrees.
TEST(SensorProfile, LivoxBinsCoverTheDatasheetsFieldOfView) {
  const std::string dir = test::SensorsDir();
  const SensorProfile mid70 = LoadSensorProfile("mid70", dir);
  EXPECT_EQ(mid70.pattern, ScanPattern::kRosette);
  EXPECT_FLOAT_EQ(mid70.elevation_deg.front() + 0.5f, 35.0f);
  EXPECT_FLOAT_EQ(mid70.elevation_deg.back() - 0.5f, -35.0f);
  const SensorProfile mid360 = LoadSensorProfile("mid360", dir);
  EXPECT_EQ(mid360.pattern, ScanPattern::kBand);
  EXPECT_FLOAT_EQ(mid360.elevation_deg.front() + 0.5f, 52.0f);
  EXPECT_FLOAT_EQ(mid360.elevation_deg.back() - 0.5f, -7.0f);
  // The datasheets' point rates (100,000 and 200,000 points/s) over a 100 ms frame.
  EXPECT_EQ(mid70.frame_points, 10000u);
  EXPECT_EQ(mid360.frame_points, 20000u);
  for (const SensorProfile* p : {&mid70, &mid360})
    for (size_t i = 1; i < p->elevation_deg.size(); ++i)
      EXPECT_FLOAT_EQ(p->elevation_deg[i - 1] - p->elevation_deg[i], 1.0f) << p->name << " " << i;
}

// The profiles taken from vendors' beam tables (their files say where from): beam count, the top
// and bottom entries of the vendor's table, the spacing where it is finest, the vendor's ring
// numbering, 1/255 intensities and room for a dual-return turn of 1800 firings (0.2 deg at
// 10 Hz, more than the 1792 columns).
struct VendorTable {
  const char* name;
  unsigned beams;
  float top, bottom;       // the table's first and last entries, degrees
  float fine_hi, fine_lo;  // the band of finest spacing, degrees ...
  float fine_step;         // ... and its mean step there
  bool ring_zero_is_top;
};

TEST(SensorProfile, VendorTablesMatchTheirSources) {
  const VendorTable tables[] = {
      // Hesai Pandar64E3X_Angle Correction File.csv (HesaiLidar_SDK_2.0): 1/6 deg from +2 to -6.
      {"pandar64", 64, 14.838f, -24.883f, 2.0f, -6.2f, 1.0f / 6, true},
      // Pandar128E4X.csv (tier4/nebula): ~0.125 deg from +2.2 to -5.9.
      {"ot128", 128, 15.139f, -24.710f, 2.21f, -5.91f, 0.125f, true},
      // Constructed from RoboSense's RS-Ruby (128) angle.csv: its ends, 0.1 deg at the horizon.
      {"rs-ruby80", 80, 15.0f, -25.0f, 0.02f, -0.6f, 0.1f, false},
  };
  for (const VendorTable& t : tables) {
    SCOPED_TRACE(t.name);
    const SensorProfile p = LoadSensorProfile(t.name, test::SensorsDir());
    ASSERT_EQ(p.beams, t.beams);
    ASSERT_EQ(p.elevation_deg.size(), t.beams);
    EXPECT_FLOAT_EQ(p.elevation_deg.front(), t.top);
    EXPECT_FLOAT_EQ(p.elevation_deg.back(), t.bottom);
    EXPECT_NEAR(p.elevation_deg.front(), 15.0, 0.2);  // datasheets: +15 ...
    EXPECT_NEAR(p.elevation_deg.back(), -25.0, 0.3);  // ... to -25 degrees
    for (size_t i = 1; i < p.elevation_deg.size(); ++i)
      EXPECT_LT(p.elevation_deg[i], p.elevation_deg[i - 1]) << "beam " << i;
    double sum = 0;
    int steps = 0;
    for (size_t i = 1; i < p.elevation_deg.size(); ++i)
      if (p.elevation_deg[i - 1] <= t.fine_hi && p.elevation_deg[i] >= t.fine_lo)
        sum += p.elevation_deg[i - 1] - p.elevation_deg[i], ++steps;
    ASSERT_GT(steps, 4);
    EXPECT_NEAR(sum / steps, t.fine_step, 0.005);
    EXPECT_EQ(p.ring_zero_is_top, t.ring_zero_is_top);
    EXPECT_EQ(p.width, 1792u);
    EXPECT_EQ(p.max_points, 2u * t.beams * 1800u);
    EXPECT_GE(p.sensor_height, 1.8f);
    EXPECT_LE(p.sensor_height, 2.0f);
  }
}

TEST(SensorProfile, ParsesEveryKey) {
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  SensorProfile p = LoadSensorProfile(WriteText(dir, "tiny.txt", kValid), dir + "/nowhere");
  EXPECT_EQ(p.name, "tiny");
  EXPECT_EQ(p.beams, 4u);
  EXPECT_EQ(p.width, 1024u);
  EXPECT_EQ(p.elevation_deg, (std::vector<float>{3.0f, 1.0f, -1.0f, -3.0f}));
  EXPECT_TRUE(p.ring_zero_is_top);
  EXPECT_FLOAT_EQ(p.sensor_height, 1.84f);
  EXPECT_FLOAT_EQ(p.min_range, 2.0f);
  EXPECT_FLOAT_EQ(p.max_range, 100.0f);
  EXPECT_EQ(p.k_xz, 0.0f);  // absent keys keep their defaults
  EXPECT_EQ(p.max_points, 0u);
  ASSERT_EQ(p.overrides.size(), 2u);
  EXPECT_EQ(p.overrides[0].first, "slope_max");
  EXPECT_FLOAT_EQ(p.overrides[0].second, 0.06f);
  EXPECT_EQ(p.overrides[1].first, "min_component");
  EXPECT_EQ(ParamsForSensor(p).min_component, 30u);
}

TEST(SensorProfile, NameLooksInTheSensorsFolderAndPathsWorkToo) {
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  WriteText(dir, "tiny.txt", kValid);
  EXPECT_EQ(LoadSensorProfile("tiny", dir).name, "tiny");
  EXPECT_EQ(LoadSensorProfile(dir + "/tiny.txt", test::SensorsDir()).name, "tiny");
  EXPECT_EQ(KnownSensorProfiles(dir), std::vector<std::string>{"tiny"});
}

TEST(SensorProfile, RoundTripsExactly) {
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  for (const char* name : kShipped) {
    SCOPED_TRACE(name);
    SensorProfile a = LoadSensorProfile(name, test::SensorsDir());
    a.k_xz = 0.0123456789f;  // values that need all nine digits
    a.k_yz = -1.0f / 3;
    a.b_x = 1.7312345f;
    a.b_y = 1e-7f;
    a.overrides = {{"t_edge", 0.1f / 3}, {"rings_far", 30.0f}};
    std::string path = dir + "/" + name + ".txt";
    WriteSensorProfile(path, a);
    SensorProfile b = LoadSensorProfile(path, dir + "/nowhere");
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.pattern, a.pattern);
    EXPECT_EQ(b.mount, a.mount);
    EXPECT_EQ(b.beams, a.beams);
    EXPECT_EQ(b.width, a.width);
    EXPECT_EQ(b.max_points, a.max_points);
    EXPECT_EQ(b.frame_points, a.frame_points);
    EXPECT_EQ(b.elevation_deg, a.elevation_deg);  // bit-exact floats
    EXPECT_EQ(b.ring_zero_is_top, a.ring_zero_is_top);
    EXPECT_EQ(b.sensor_height, a.sensor_height);
    EXPECT_EQ(b.min_range, a.min_range);
    EXPECT_EQ(b.max_range, a.max_range);
    EXPECT_EQ(b.k_xz, a.k_xz);
    EXPECT_EQ(b.k_yz, a.k_yz);
    EXPECT_EQ(b.b_x, a.b_x);
    EXPECT_EQ(b.b_y, a.b_y);
    EXPECT_EQ(b.overrides, a.overrides);
  }
}

TEST(SensorProfile, UnknownNameListsTheKnownProfiles) {
  try {
    LoadSensorProfile("hdl128x", test::SensorsDir());
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("unknown sensor profile 'hdl128x'"), std::string::npos) << m;
    EXPECT_NE(m.find("known: hdl32e, hdl64e, mid360, mid70, os1-128, os1-64, ot128, pandar64, "
                     "rs-ruby80, vlp16, vlp32c"),
              std::string::npos)
        << m;
  }
}

struct BadCase {
  const char* what;
  std::string text;
  int line;
  const char* says;
};

// kValid with line `line` (1-based) replaced by `replacement` ("" deletes it).
std::string Edit(int line, const std::string& replacement) {
  std::string out;
  std::string text = kValid;
  int n = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    ++n;
    std::string current = text.substr(start, end - start);
    if (n != line)
      out += current + "\n";
    else if (!replacement.empty())
      out += replacement + "\n";
    start = end + 1;
  }
  return out;
}

TEST(SensorProfile, MalformedFilesNameTheFileAndTheLine) {
  // kValid's lines: 1 comment, 2 name, 3 beams, 4 width, 5 elevation_deg, 6 continuation,
  // 7 ring_zero_is_top, 8 comment, 9 sensor_height, 10 min_range, 11 max_range,
  // 12-13 param.
  const BadCase cases[] = {
      {"unknown key", Edit(9, "sensor_hieght 1.8"), 9, "unknown key 'sensor_hieght'"},
      {"duplicate key", Edit(1, "width 2048"), 4, "duplicate key 'width' (first on line 1)"},
      {"bad number", Edit(8, "min_range 0.5x"), 8, "'0.5x' is not a finite number"},
      {"intensity scale", Edit(8, "intensity_scale 0.0039"), 8, "unknown key 'intensity_scale'"},
      {"bad number in table", Edit(6, "  -1.0 minus3"), 6, "'minus3' is not a finite number"},
      {"number in the table", Edit(6, "  -1.0 -3,0"), 6, "'-3,0' is not a finite number"},
      {"non-finite", Edit(10, "min_range 1e99"), 10, "not a finite number"},
      {"whole number", Edit(3, "beams 4.0"), 3, "'4.0' is not a whole number"},
      {"too few elevations", Edit(6, "  -1.0"), 5, "elevation_deg has 3 values but beams is 4"},
      {"too many elevations", Edit(6, "  -1.0 -3.0 -5.0"), 5, "has 5 values but beams is 4"},
      {"not descending", Edit(6, "  1.0 -3.0"), 5, "strictly descending"},
      {"ascending", Edit(5, "elevation_deg -3.0 -1.0"), 5, "strictly descending"},
      {"width not /64", Edit(4, "width 1800"), 4, "width 1800 must be a positive multiple of 64"},
      {"max_points 0", Edit(4, "width 1024\nmax_points 0"), 5, "max_points must be 1..1e8"},
      {"max_points huge", Edit(4, "width 1024\nmax_points 100000001"), 5,
       "max_points must be 1..1e8"},
      {"frame_points 0", Edit(4, "width 1024\nframe_points 0"), 5, "frame_points must be 1..1e7"},
      {"frame_points huge", Edit(4, "width 1024\nframe_points 10000001"), 5,
       "frame_points must be 1..1e7"},
      {"unknown param", Edit(12, "param slope_maximum 0.06"), 12,
       "unknown parameter 'slope_maximum'"},
      {"param value rejected", Edit(13, "param min_component 2.5"), 13, "whole number"},
      {"duplicate param", Edit(13, "param slope_max 0.07"), 13, "duplicate param 'slope_max'"},
      {"param arity", Edit(12, "param slope_max"), 12, "param expects a name and a value"},
      {"two values", Edit(9, "sensor_height 1.8 1.9"), 9, "expects exactly one value, got 2"},
      {"no value", Edit(2, "name"), 2, "expects exactly one value, got 0"},
      {"ring flag", Edit(7, "ring_zero_is_top yes"), 7, "ring_zero_is_top must be 0 or 1"},
      {"pattern", Edit(7, "pattern spiral"), 7,
       "pattern must be one of spinning, rosette, band, got 'spiral'"},
      {"mount", Edit(7, "mount auto"), 7, "mount must be one of fixed, per_frame, got 'auto'"},
      {"stray numbers", Edit(8, "1.0 2.0"), 8, "numbers without a key"},
      {"range order", Edit(11, "max_range 1.5"), 11, "max_range must be larger than min_range"},
      {"negative height", Edit(9, "sensor_height -1.73"), 9, "sensor_height must be > 0"},
      {"missing name", Edit(2, ""), 13, "without the required key 'name'"},
      {"missing table", Edit(5, ""), 5, "numbers without a key"},
  };
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  int index = 0;
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    std::string path = WriteText(dir, "bad" + std::to_string(index++) + ".txt", c.text);
    try {
      LoadSensorProfile(path, dir);
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const IoError& e) {
      std::string m = e.what();
      EXPECT_EQ(m.rfind(path + ": line " + std::to_string(c.line) + ": ", 0), 0u) << m;
      EXPECT_NE(m.find(c.says), std::string::npos) << m;
    }
  }
}

TEST(SensorProfile, MissingTableReportedAtTheEnd) {
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  std::string path = WriteText(dir, "p.txt", "name x\nbeams 2\nwidth 64\n");
  try {
    LoadSensorProfile(path, dir);
    FAIL() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": line 4: end of file without the required key "
                                                "'elevation_deg'"),
              std::string::npos)
        << e.what();
  }
}

TEST(SensorProfile, MissingFileAndUnwritableFolderAreIoErrorsAnUnknownNameInvalid) {
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  try {
    LoadSensorProfile(dir + "/absent.txt", dir);
    ADD_FAILURE() << "a missing profile file was read";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), dir + "/absent.txt: no such sensor profile file");
    EXPECT_EQ(e.error_number(), ENOENT);
  }
  EXPECT_THROW(LoadSensorProfile("absent", dir), std::invalid_argument);  // a name: none such
  EXPECT_THROW(WriteSensorProfile(dir + "/no/such/folder.txt",
                                  LoadSensorProfile("vlp16", test::SensorsDir())),
               IoError);
}

// ParamsForSensor's std::invalid_argument message for `s`, or "no exception".
std::string ParamsError(const SensorProfile& s) {
  try {
    ParamsForSensor(s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

// Profiles built in code get the bounds the reader enforces, and a grid that fits its integers.
TEST(SensorProfile, ParamsForSensorBoundsTheGridTiltAndRange) {
  const SensorProfile good = LoadSensorProfile("hdl64e", test::SensorsDir());
  EXPECT_NO_THROW(ParamsForSensor(good));
  SensorProfile s = good;
  s.overrides.push_back({"rings_near", 4e9f});
  EXPECT_NE(ParamsError(s).find("at most 4096 rings"), std::string::npos) << ParamsError(s);
  s = good;
  s.overrides.push_back({"sectors_far", 2048.0f});
  s.overrides.push_back({"rings_far", 4000.0f});
  EXPECT_NE(ParamsError(s).find("4194304 cells"), std::string::npos) << ParamsError(s);
  s = good;
  s.k_xz = 1e30f;
  EXPECT_NE(ParamsError(s).find("k_xz and k_yz must lie in -1..1"), std::string::npos)
      << ParamsError(s);
  s = good;
  s.max_range = 1e6f;
  EXPECT_NE(ParamsError(s).find("max_range be at most 1000 m"), std::string::npos)
      << ParamsError(s);
}

// A subnormal parameter (a device may flush it) is an error naming it; 0 and the smallest normal
// float are fine.
TEST(SensorProfile, ParamsForSensorRejectsSubnormalParameters) {
  const SensorProfile good = LoadSensorProfile("hdl64e", test::SensorsDir());
  for (const std::string& name : ParamNames()) {
    if (name == "rings_near" || name == "rings_far" || name == "sectors_near" ||
        name == "sectors_far" || name == "min_component" || name == "occ_rows" ||
        name == "occ_step_rows" || name == "comp_seed_min" || name == "rise_carry" ||
        name == "ring_res_near" || name == "ring_res_far")
      continue;  // whole numbers, or must be positive (checked before)
    for (float tiny : {1e-40f, -3e-39f}) {
      SensorProfile s = good;
      s.overrides.push_back({name, tiny});
      const std::string m = ParamsError(s);
      EXPECT_NE(m.find("parameter " + name + " is "), std::string::npos) << name << ": " << m;
      EXPECT_NE(m.find("subnormal"), std::string::npos) << name << ": " << m;
    }
    for (float fine : {0.0f, std::numeric_limits<float>::min()}) {
      SensorProfile s = good;
      s.overrides.push_back({name, fine});
      EXPECT_NO_THROW(ParamsForSensor(s)) << name << " = " << fine;
    }
  }
  SensorProfile s = good;
  s.overrides.push_back({"ring_res_far", 1e-40f});
  EXPECT_NE(ParamsError(s).find("parameter ring_res_far is "), std::string::npos) << ParamsError(s);
  s = good;
  s.k_yz = 1e-40f;
  EXPECT_NE(ParamsError(s).find("parameter k_yz is "), std::string::npos) << ParamsError(s);
  s = good;
  s.min_range = 1e-20f;  // its square is subnormal
  EXPECT_NE(ParamsError(s).find("parameter min_range2 (min_range squared) is "), std::string::npos)
      << ParamsError(s);
}

// ApplySettings' std::invalid_argument message, or "no exception".
std::string SettingsError(SensorProfile s,
                          const std::vector<std::pair<std::string, std::string>>& settings) {
  try {
    ApplySettings(s, settings);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

// A setting is the profile line `NAME VALUE` or `param NAME VALUE`: the profile it gives equals
// the one read from a file holding that line, and the reader's checks apply.
TEST(SensorProfile, SettingsActAsProfileLines) {
  test::ScopedDir scoped;
  const std::string& dir = scoped.path;
  const std::string edited =
      WriteText(dir, "edited.txt", Edit(9, "sensor_height 1.9") + "param h_athr 0.2\n");
  const SensorProfile expected = LoadSensorProfile(edited, dir);
  SensorProfile s = LoadSensorProfile(WriteText(dir, "valid.txt", kValid), dir);
  ApplySettings(s, {{"sensor_height", "1.9"}, {"h_athr", "0.5"}, {"h_athr", "0.2"}});
  EXPECT_EQ(s.sensor_height, expected.sensor_height);
  EXPECT_EQ(s.overrides, expected.overrides);  // the later h_athr replaces the earlier
  const Params p = ParamsForSensor(s);
  EXPECT_EQ(p.sensor_height, 1.9f);
  EXPECT_EQ(p.h_athr, 0.2f);
  EXPECT_EQ(p.h_noise, -1.9f - 2.0f);  // the noise floor follows the mount height
  ApplySettings(s, {{"max_points", "5000"},
                    {"ring_zero_is_top", "0"},
                    {"k_xz", "-0.05"},
                    {"min_range", "3"},
                    {"max_range", "80"},
                    {"mount", "per_frame"}});
  EXPECT_EQ(s.mount, MountSource::kPerFrame);
  EXPECT_EQ(s.max_points, 5000u);
  EXPECT_FALSE(s.ring_zero_is_top);
  EXPECT_EQ(s.k_xz, -0.05f);
  EXPECT_EQ(ParamsForSensor(s).max_range2, 80.0f * 80.0f);
  ApplySettings(s, {});  // nothing: nothing changes
  EXPECT_EQ(s.max_points, 5000u);
  // Every name SettingNames lists is a setting; the profile's geometry is not.
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  for (const std::string& name : SettingNames()) {
    const std::string m = SettingsError(hdl64e, {{name, "1"}});
    EXPECT_EQ(m.find("no setting"), std::string::npos) << name << ": " << m;
  }
  const std::vector<std::string> names = SettingNames();
  for (const std::string& name : ParamNames())
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(SensorProfile, BadSettingsNameTheSettingAndTheProblem) {
  const SensorProfile hdl64e = LoadSensorProfile("hdl64e", test::SensorsDir());
  const struct {
    std::vector<std::pair<std::string, std::string>> settings;
    const char* says;
  } cases[] = {
      {{{"sensr_height", "1.9"}},
       "sensr_height=1.9: no setting 'sensr_height' (did you mean "
       "sensor_height?); known: sensor_height, min_range,"},
      {{{"xyz", "1"}}, "xyz=1: no setting 'xyz'; known: "},
      {{{"beams", "32"}}, "beams=32: no setting 'beams'"},  // the geometry is the profile's
      {{{"sensor_height", "0"}}, "sensor_height=0: sensor_height must be > 0"},
      {{{"sensor_height", "1.9m"}}, "sensor_height=1.9m: sensor_height: '1.9m' is not a finite"},
      {{{"h_athr", "nan"}}, "h_athr=nan: h_athr: 'nan' is not a finite number"},
      {{{"min_component", "-3"}}, "min_component=-3: parameter min_component expects a whole"},
      {{{"ring_zero_is_top", "2"}}, "ring_zero_is_top=2: ring_zero_is_top must be 0 or 1"},
      {{{"max_points", "1.5"}}, "max_points=1.5: max_points: '1.5' is not a whole number"},
      {{{"k_yz", "3"}}, "k_yz=3: k_yz must be within -1..1"},
      // the profile as a whole, after every setting
      {{{"min_range", "150"}}, "min_range=150: max_range must be larger than min_range"},
      {{{"sectors_near", "100"}, {"h_athr", "0.2"}},
       "sectors_near=100, h_athr=0.2: sensor profile 'hdl64e': sectors_near and sectors_far must "
       "divide the image width"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.says);
    const std::string m = SettingsError(hdl64e, c.settings);
    EXPECT_EQ(m.rfind(c.says, 0), 0u) << m;
  }
  // settings that only hold together are checked together
  EXPECT_EQ(SettingsError(hdl64e, {{"min_range", "150"}, {"max_range", "200"}}), "no exception");
}

}  // namespace
}  // namespace lpir
