// Sensor profiles: parses and writes the `key value...` text files of sensors/ (format in
// sensors/README.md), validating every line strictly.
#include "host/io/sensor_profile.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "host/io/file_bytes.h"
#include "host/io/io_error.h"
#include "host/io/suggest.h"
#include "reference_cpu/params.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;

// Splits a line into whitespace-separated tokens after dropping a `#` comment.
std::vector<std::string> Tokens(const std::string& line) {
  std::string text = line.substr(0, line.find('#'));
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string t;
  while (in >> t) out.push_back(t);
  return out;
}

bool IsNumberStart(const std::string& t) {
  char c = t[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

// Token `t` of `key` as a float, the whole token a finite number; std::invalid_argument with the
// problem otherwise.
float ParseFloat(const std::string& key, const std::string& t) {
  errno = 0;
  char* end = nullptr;
  const float v = std::strtof(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v))
    throw std::invalid_argument(key + ": '" + t + "' is not a finite number");
  return v;
}

// Token `t` of `key` as a whole number of at most 9 digits; std::invalid_argument otherwise.
unsigned ParseUnsigned(const std::string& key, const std::string& t) {
  if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos)
    throw std::invalid_argument(key + ": '" + t + "' is not a whole number");
  return static_cast<unsigned>(std::stoul(t));
}

// Token `t` of `key` as a whole number within lo..hi; std::invalid_argument otherwise, saying
// `range` when the number lies outside.
unsigned ParseCount(const std::string& key, const std::string& t, unsigned lo, unsigned hi,
                    const char* range) {
  const unsigned n = ParseUnsigned(key, t);
  if (n < lo || n > hi) throw std::invalid_argument(range);
  return n;
}

// Token `t` of `key` (k_xz, k_yz) as a tilt slope within -1..1; std::invalid_argument otherwise.
float ParseTiltSlope(const std::string& key, const std::string& t) {
  const float k = ParseFloat(key, t);
  if (!(std::fabs(k) <= kMaxProfileTiltSlope))
    throw std::invalid_argument(key + " must be within -1..1 (a mount tilt of at most 45 degrees)");
  return k;
}

// The words of the enumerated keys, in enum order.
const char* const kPatternNames[] = {"spinning", "rosette", "band"};
const char* const kMountNames[] = {"fixed", "per_frame"};

// The index of `v` among `names`; std::invalid_argument listing them otherwise.
template <size_t N>
size_t ParseWord(const std::string& key, const std::string& v, const char* const (&names)[N]) {
  std::string all;
  for (size_t i = 0; i < N; ++i) {
    if (v == names[i]) return i;
    all += std::string(i ? ", " : "") + names[i];
  }
  throw std::invalid_argument(key + " must be one of " + all + ", got '" + v + "'");
}

[[noreturn]] void Fail(const std::string& problem) { throw std::invalid_argument(problem); }

// What follows a key on its line: one value (set by the row's `set`), a list of numbers that may
// continue on the following lines (the row's `list`), or `NAME VALUE` of a parameter.
enum class Shape { kOne, kList, kParam };

// One key of a profile file. `set` parses and checks token `v` of `key` into the profile, with
// std::invalid_argument naming the problem. `settable`: a setting (ApplySettings) may change it,
// as it tunes the segmentation of a sensor already described; the geometry (beams, width, the
// lists) is the file's alone.
struct Key {
  const char* key;
  Shape shape;
  bool required;
  bool settable;
  void (*set)(SensorProfile& p, const std::string& key, const std::string& v);
  std::vector<float> SensorProfile::*list = nullptr;
};

// Every key a profile may hold, one row each; every key but `param` appears at most once (a
// `param` line once per parameter name). SettingNames lists the settable ones in this order.
const Key kKeys[] = {
    {"name", Shape::kOne, true, false, [](auto& p, auto&, auto& v) { p.name = v; }},
    {"pattern", Shape::kOne, false, false,
     [](auto& p, auto& k, auto& v) {
       p.pattern = static_cast<ScanPattern>(ParseWord(k, v, kPatternNames));
     }},
    {"beams", Shape::kOne, true, false,
     [](auto& p, auto& k, auto& v) {
       p.beams = ParseCount(k, v, 1, 4096, "beams must be 1..4096");
     }},
    {"width", Shape::kOne, true, false,
     [](auto& p, auto& k, auto& v) {
       p.width = ParseUnsigned(k, v);
       if (p.width == 0 || p.width % 64 != 0 || p.width > 65536)
         Fail("width " + v + " must be a positive multiple of 64 (at most 65536)");
     }},
    {"elevation_deg", Shape::kList, true, false, nullptr, &SensorProfile::elevation_deg},
    {"beam_origin_z", Shape::kList, false, false, nullptr, &SensorProfile::beam_origin_z},
    {"sensor_height", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) {
       p.sensor_height = ParseFloat(k, v);
       if (!(p.sensor_height > 0)) Fail("sensor_height must be > 0");
     }},
    {"min_range", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) {
       p.min_range = ParseFloat(k, v);
       if (p.min_range < 0) Fail("min_range must be >= 0");
     }},
    // Bounded so that every valid point's coordinates and corrected height stay inside the
    // fixed-point ranges of coarse_segment and feature_maps (mm in int32, 0.1 mm moments in int64):
    // a larger one let a point with z = 1e20 through to an overflowing float -> int64 conversion.
    {"max_range", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) {
       p.max_range = ParseFloat(k, v);
       if (!(p.max_range <= kMaxProfileRange)) Fail("max_range must be at most 1000 m");
     }},
    // A mount tilt of at most 45 degrees: |z_t| <= 3 max_range (eq. 3). k_xz = 1e30 made z_t
    // overflow the same conversion.
    {"k_xz", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) { p.k_xz = ParseTiltSlope(k, v); }},
    {"k_yz", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) { p.k_yz = ParseTiltSlope(k, v); }},
    {"ring_zero_is_top", Shape::kOne, false, true,
     [](auto& p, auto&, auto& v) {
       if (v != "0" && v != "1") Fail("ring_zero_is_top must be 0 or 1, got '" + v + "'");
       p.ring_zero_is_top = v == "1";
     }},
    {"max_points", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) {
       p.max_points = ParseCount(k, v, 1, 100000000, "max_points must be 1..1e8");
     }},
    {"frame_points", Shape::kOne, false, false,
     [](auto& p, auto& k, auto& v) {
       p.frame_points = ParseCount(k, v, 1, 10000000, "frame_points must be 1..1e7");
     }},
    {"mount", Shape::kOne, false, true,
     [](auto& p, auto& k, auto& v) {
       p.mount = static_cast<MountSource>(ParseWord(k, v, kMountNames));
     }},
    {"b_x", Shape::kOne, false, false, [](auto& p, auto& k, auto& v) { p.b_x = ParseFloat(k, v); }},
    {"b_y", Shape::kOne, false, false, [](auto& p, auto& k, auto& v) { p.b_y = ParseFloat(k, v); }},
    {"param", Shape::kParam, false, false, nullptr},
};

// The row of `key`; nullptr when no key has that name.
const Key* FindKey(const std::string& key) {
  for (const Key& k : kKeys)
    if (key == k.key) return &k;
  return nullptr;
}

std::string KnownKeys() {
  std::string all;
  for (const Key& k : kKeys) all += std::string(all.empty() ? "" : ", ") + k.key;
  return all;
}

// Parameter `name` = `value` checked against the parameter table (ApplyOverride's rules);
// std::invalid_argument with the problem.
void CheckParam(const std::string& name, float value) {
  Params defaults = DefaultParams();
  if (!ApplyOverride(defaults, name, value))
    throw std::invalid_argument("unknown parameter '" + name + "'");
}

// The reader of one file: throws IoError(path, "line N: ...") on the first problem.
class Parser {
 public:
  explicit Parser(const std::string& path) : path_(path) {}

  [[noreturn]] void Fail(int line, const std::string& problem) const {
    throw IoError(path_, "line " + std::to_string(line) + ": " + problem);
  }

  float Float(int line, const std::string& key, const std::string& t) const {
    try {
      return ParseFloat(key, t);
    } catch (const std::invalid_argument& e) {
      Fail(line, e.what());
    }
  }

  SensorProfile Parse(const std::string& text) {
    SensorProfile p;
    p.overrides.clear();
    std::map<std::string, int> seen;          // key -> line of its first appearance
    std::map<std::string, int> params_seen;   // override name -> line
    std::vector<float>* open_list = nullptr;  // the list the previous line was (or continued)
    std::string open_key;
    std::istringstream in(text);
    std::string raw;
    int line = 0;
    while (std::getline(in, raw)) {
      ++line;
      std::vector<std::string> tok = Tokens(raw);
      if (tok.empty()) continue;  // blank and comment lines keep a list open
      if (IsNumberStart(tok[0])) {
        if (!open_list)
          Fail(line,
               "numbers without a key (only elevation_deg and beam_origin_z continue on "
               "following lines)");
        for (const std::string& t : tok) open_list->push_back(Float(line, open_key, t));
        continue;
      }
      open_list = nullptr;
      const std::string& key = tok[0];
      const Key* row = FindKey(key);
      if (!row) Fail(line, "unknown key '" + key + "' (known: " + KnownKeys() + ")");
      if (row->shape != Shape::kParam) {
        auto it = seen.find(key);
        if (it != seen.end())
          Fail(line,
               "duplicate key '" + key + "' (first on line " + std::to_string(it->second) + ")");
        seen[key] = line;
      }
      const size_t values = tok.size() - 1;
      if (row->shape == Shape::kList) {
        open_list = &(p.*row->list);
        open_key = key;
        for (size_t i = 1; i < tok.size(); ++i) open_list->push_back(Float(line, key, tok[i]));
        continue;
      }
      if (row->shape == Shape::kParam) {
        if (values != 2) Fail(line, "param expects a name and a value: param NAME VALUE");
        const std::string& name = tok[1];
        float v = Float(line, "param " + name, tok[2]);
        try {
          CheckParam(name, v);
        } catch (const std::invalid_argument& e) {
          Fail(line, std::string("param: ") + e.what());
        }
        auto it = params_seen.find(name);
        if (it != params_seen.end())
          Fail(line,
               "duplicate param '" + name + "' (first on line " + std::to_string(it->second) + ")");
        params_seen[name] = line;
        p.overrides.emplace_back(name, v);
        continue;
      }
      if (values != 1)
        Fail(line, key + " expects exactly one value, got " + std::to_string(values));
      try {
        row->set(p, key, tok[1]);
      } catch (const std::invalid_argument& e) {
        Fail(line, e.what());
      }
    }
    std::string required;
    for (const Key& k : kKeys)
      if (k.required) required += std::string(required.empty() ? "" : ", ") + k.key;
    for (const Key& k : kKeys) {
      if (k.required && !seen.count(k.key))
        Fail(line + 1, std::string("end of file without the required key '") + k.key +
                           "' (required: " + required + ")");
    }
    const int elevation_line = seen["elevation_deg"];
    const int origin_line = seen.count("beam_origin_z") ? seen["beam_origin_z"] : 0;
    if (p.elevation_deg.size() != p.beams)
      Fail(elevation_line, "elevation_deg has " + std::to_string(p.elevation_deg.size()) +
                               " values but beams is " + std::to_string(p.beams));
    for (size_t i = 0; i < p.elevation_deg.size(); ++i) {
      if (p.elevation_deg[i] < -90 || p.elevation_deg[i] > 90)
        Fail(elevation_line, "elevation_deg value " + std::to_string(i) + " is outside -90..90");
      if (i > 0 && !(p.elevation_deg[i] < p.elevation_deg[i - 1]))
        Fail(elevation_line, "elevation_deg must be strictly descending (top beam first): value " +
                                 std::to_string(i) + " does not lie below value " +
                                 std::to_string(i - 1));
    }
    if (origin_line && p.beam_origin_z.size() != p.beams)
      Fail(origin_line, "beam_origin_z has " + std::to_string(p.beam_origin_z.size()) +
                            " values but beams is " + std::to_string(p.beams));
    for (float oz : p.beam_origin_z)
      if (!(oz >= -1.0f && oz <= 1.0f))
        Fail(origin_line, "beam_origin_z values must be within 1 m");
    if (!(p.max_range > p.min_range)) {
      int at = seen.count("max_range") ? seen["max_range"] : seen["min_range"];
      Fail(at, "max_range must be larger than min_range");
    }
    return p;
  }

 private:
  std::string path_;
};

std::string FormatFloat(float v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.9g", static_cast<double>(v));
  return buf;
}

SensorProfile LoadFile(const std::string& path) {
  std::vector<char> bytes = ReadFileBytes(path);
  return Parser(path).Parse(std::string(bytes.begin(), bytes.end()));
}

bool IsFile(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

}  // namespace

const char* PatternName(ScanPattern pattern) { return kPatternNames[static_cast<int>(pattern)]; }
const char* MountName(MountSource mount) { return kMountNames[static_cast<int>(mount)]; }

SensorProfile LoadSensorProfile(const std::string& name_or_path, const std::string& sensors_dir) {
  // A bare name is looked up in sensors_dir first, so that a stray file of the same name in the
  // working folder cannot shadow a shipped profile.
  if (!name_or_path.empty() && name_or_path.find('/') == std::string::npos) {
    std::string candidate = sensors_dir + "/" + name_or_path + ".txt";
    if (IsFile(candidate)) return LoadFile(candidate);
  }
  if (IsFile(name_or_path)) return LoadFile(name_or_path);
  const std::vector<std::string> names = KnownSensorProfiles(sensors_dir);
  // a path (it names a folder) to a file that is not there: a missing file, not a bad name
  if (name_or_path.find('/') != std::string::npos)
    throw IoError(name_or_path, "no such sensor profile file", ENOENT);
  std::string known;
  for (const std::string& k : names) known += std::string(known.empty() ? "" : ", ") + k;
  throw std::invalid_argument(
      "unknown sensor profile '" + name_or_path + "'" + DidYouMean(name_or_path, names) +
      "; known: " + (known.empty() ? "(none in " + sensors_dir + ")" : known));
}

std::vector<std::string> SettingNames() {
  std::vector<std::string> names;
  for (const Key& k : kKeys)
    if (k.settable) names.push_back(k.key);
  for (const std::string& name : ParamNames()) names.push_back(name);
  return names;
}

void ApplySettings(SensorProfile& profile,
                   const std::vector<std::pair<std::string, std::string>>& settings) {
  std::string all;  // "a=1, b=2", for a problem of the profile as a whole
  for (const auto& [name, value] : settings) {
    const std::string setting = name + "=" + value;
    all += (all.empty() ? "" : ", ") + setting;
    const Key* row = FindKey(name);
    const bool key = row && row->settable;
    const std::vector<std::string> params = ParamNames();
    try {
      if (key) {
        row->set(profile, name, value);
      } else if (std::find(params.begin(), params.end(), name) != params.end()) {
        const float v = ParseFloat(name, value);
        CheckParam(name, v);
        auto same = [&name = name](const auto& o) { return o.first == name; };
        profile.overrides.erase(
            std::remove_if(profile.overrides.begin(), profile.overrides.end(), same),
            profile.overrides.end());
        profile.overrides.emplace_back(name, v);
      } else {
        std::string known;
        for (const std::string& k : SettingNames()) known += (known.empty() ? "" : ", ") + k;
        throw std::invalid_argument("no setting '" + name + "'" + DidYouMean(name, SettingNames()) +
                                    "; known: " + known);
      }
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(setting + ": " + e.what());
    }
  }
  try {
    if (!(profile.max_range > profile.min_range))
      throw std::invalid_argument("max_range must be larger than min_range");
    ParamsForSensor(profile);  // the grid's and the parameters' rules over the whole profile
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(all + ": " + e.what());
  }
}

std::vector<std::string> KnownSensorProfiles(const std::string& sensors_dir) {
  std::set<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(sensors_dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".txt" && it->is_regular_file(ec))
      names.insert(it->path().stem().string());
  }
  return std::vector<std::string>(names.begin(), names.end());
}

void WriteSensorProfile(const std::string& path, const SensorProfile& p) {
  if (p.name.empty() || p.name.find_first_of(" \t\r\n#") != std::string::npos)
    throw IoError(path, "cannot write a profile whose name '" + p.name + "' is not one word");
  std::string s = "# Sensor profile (format: sensors/README.md).\n";
  s += "name " + p.name + "\n";
  s += std::string("pattern ") + PatternName(p.pattern) + "\n";
  s += std::string("mount ") + MountName(p.mount) + "\n";
  s += "beams " + std::to_string(p.beams) + "\n";
  s += "width " + std::to_string(p.width) + "\n";
  if (p.max_points) s += "max_points " + std::to_string(p.max_points) + "\n";
  if (p.frame_points) s += "frame_points " + std::to_string(p.frame_points) + "\n";
  s += "elevation_deg";
  for (size_t i = 0; i < p.elevation_deg.size(); ++i) {
    if (i > 0 && i % 8 == 0) s += "\n ";
    s += " " + FormatFloat(p.elevation_deg[i]);
  }
  s += "\n";
  if (!p.beam_origin_z.empty()) {
    s += "beam_origin_z";
    for (size_t i = 0; i < p.beam_origin_z.size(); ++i) {
      if (i > 0 && i % 8 == 0) s += "\n ";
      s += " " + FormatFloat(p.beam_origin_z[i]);
    }
    s += "\n";
  }
  s += std::string("ring_zero_is_top ") + (p.ring_zero_is_top ? "1" : "0") + "\n";
  s += "sensor_height " + FormatFloat(p.sensor_height) + "\n";
  s += "min_range " + FormatFloat(p.min_range) + "\n";
  s += "max_range " + FormatFloat(p.max_range) + "\n";
  s += "k_xz " + FormatFloat(p.k_xz) + "\n";
  s += "k_yz " + FormatFloat(p.k_yz) + "\n";
  s += "b_x " + FormatFloat(p.b_x) + "\n";
  s += "b_y " + FormatFloat(p.b_y) + "\n";
  for (const auto& [name, value] : p.overrides)
    s += "param " + name + " " + FormatFloat(value) + "\n";
  WriteFileBytes(path, s.data(), s.size());
}

}  // namespace lpir
