// The module's functions: cloud and label files (host/io/), scores (host/eval/), the scene
// simulator (apps/sim/), the sensor profiles and the Vulkan devices. File reading and simulation
// release the GIL.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "apps/sim/scene.h"
#include "arrays.h"
#include "bindings.h"
#include "host/eval/by_class.h"
#include "host/eval/by_range.h"
#include "host/eval/metrics.h"
#include "host/eval/ontology.h"
#include "host/io/cloud_file.h"
#include "host/io/label_file.h"
#include "host/io/output_paths.h"
#include "host/io/sensor_profile.h"
#include "host/vk/device.h"
#include "host/vk/instance.h"

namespace lpir::python {
namespace {

py::object ReadCloudPy(py::handle path_arg, py::handle nuscenes, bool with_ring) {
  const std::string path = PathArg(path_arg);
  ReadOptions options;
  if (!nuscenes.is_none())
    options.bin_layout = nuscenes.cast<bool>() ? BinLayout::kNuScenes5 : BinLayout::kKitti4;
  Cloud cloud;
  std::string note;
  {
    py::gil_scoped_release nogil;
    cloud = ReadCloud(path, options, &note);
  }
  // stacklevel 1: the warning names the caller's line (this function has no Python frame).
  if (!note.empty() && PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1) != 0)
    throw py::error_already_set();  // warnings turned into errors
  py::object ring = py::none();
  if (with_ring && !cloud.ring.empty()) ring = VectorArray(std::vector<int32_t>(cloud.ring));
  py::array points = CloudArray(std::move(cloud));
  if (with_ring) return py::make_tuple(points, ring);
  return std::move(points);
}

py::array ReadLabelsPy(py::handle path_arg, size_t expected_points) {
  const std::string path = PathArg(path_arg);
  std::vector<uint32_t> labels;
  {
    py::gil_scoped_release nogil;
    labels = ReadLabelFile(path, expected_points);
  }
  return VectorArray(std::move(labels));
}

void WriteLabelsPy(py::handle path_arg, py::handle labels) {
  const std::string path = PathArg(path_arg);
  const std::vector<uint32_t> values = ToUint32(labels, "labels", 0, true);
  py::gil_scoped_release nogil;
  WriteLabelFile(path, values);
}

// A prediction: 1-D bools or integers, any non-zero value ground.
Labels ToPrediction(py::handle pred, const std::string& name, size_t expected) {
  const std::vector<uint32_t> values = ToUint32(pred, name, expected, true);
  Labels labels(values.size());
  for (size_t i = 0; i < values.size(); ++i) labels[i] = values[i] != 0;
  return labels;
}

// x, y, z of (N, >= 3) points (intensity 0): protocol pw reads each point's z, by_range its x
// and y.
Cloud PointsOf(py::handle points, const std::string& name, size_t expected) {
  py::array a = py::array::ensure(points);
  if (!a || a.ndim() != 2 || a.shape(1) < 3 || size_t(a.shape(0)) != expected ||
      (a.dtype().kind() != 'f' && a.dtype().kind() != 'i' && a.dtype().kind() != 'u'))
    throw py::value_error(name + " must be an (" + std::to_string(expected) +
                          ", 3 or 4) array of numbers: protocol pw reads each point's z, "
                          "by_range its x and y");
  auto f = py::array_t<float, py::array::forcecast>::ensure(a);
  auto view = f.unchecked<2>();
  Cloud cloud;
  cloud.xyzi.reserve(4 * expected);
  for (py::ssize_t i = 0; i < py::ssize_t(expected); ++i)
    cloud.Push(view(i, 0), view(i, 1), view(i, 2), 0.0f);
  return cloud;
}

// The counts as the CLI's JSON gives them: tp, fp, fn, tn, ignored.
void AddCounts(const Counts& c, py::dict& d) {
  d["tp"] = c.tp, d["fp"] = c.fp, d["fn"] = c.fn, d["tn"] = c.tn, d["ignored"] = c.ignored;
}

// evaluate's by_class: a dict per ground-truth class, ascending, as `evaluate --by-class --json`
// gives it for the one protocol.
py::list ByClassList(const ClassBreakdown& b, Ontology ontology) {
  py::list out;
  for (const auto& [cls, t] : b.classes()) {
    py::dict d;
    d["class"] = cls, d["name"] = ClassName(ontology, cls), d["points"] = t.points;
    d["predicted_ground"] = t.predicted_ground;
    d["share"] = double(t.predicted_ground) / double(t.points);
    AddCounts(t.counts[0], d);
    out.append(d);
  }
  return out;
}

// evaluate's by_range: a dict per band of horizontal range, as `evaluate --by-range --json` gives
// it for the one protocol ("to" None for the last band).
py::list ByRangeList(const RangeBreakdown& b) {
  py::list out;
  for (size_t band = 0; band < kRangeBands; ++band) {
    const RangeTally& t = b.bands()[band];
    py::dict d;
    d["band"] = RangeBandName(band);
    d["from"] = band ? double(kRangeBandEdges[band - 1]) : 0.0;
    d["to"] = band < kRangeBandEdges.size() ? py::object(py::float_(kRangeBandEdges[band]))
                                            : py::object(py::none());
    d["points"] = t.points;
    AddCounts(t.counts[0], d);
    out.append(d);
  }
  return out;
}

py::dict ScoresDict(const Scores& s) {
  py::dict d;
  d["precision"] = s.precision, d["recall"] = s.recall, d["f1"] = s.f1, d["iou"] = s.iou;
  return d;
}

// One frame (arrays) or a sequence (lists or tuples of arrays, one per frame).
bool IsSequence(py::handle pred) {
  if (!py::isinstance<py::list>(pred) && !py::isinstance<py::tuple>(pred)) return false;
  const py::sequence s = py::reinterpret_borrow<py::sequence>(pred);
  return s.size() > 0 && (py::isinstance<py::array>(s[0]) || py::isinstance<py::list>(s[0]) ||
                          py::isinstance<py::tuple>(s[0]));
}

py::dict EvaluatePy(py::handle pred, py::handle gt, py::handle protocol_arg,
                    const std::string& ontology_name, py::handle points, bool by_class,
                    bool by_range) {
  const Ontology ontology = ParseOntology(ontology_name);
  const Protocol protocol = protocol_arg.is_none()
                                ? ProtocolsOf(ontology).front()
                                : ParseProtocol(protocol_arg.cast<std::string>(), ontology);
  std::vector<py::object> preds, gts, clouds;
  const bool sequence = IsSequence(pred);
  if (sequence) {
    for (py::handle h : pred) preds.push_back(py::reinterpret_borrow<py::object>(h));
    for (py::handle h : py::iter(gt)) gts.push_back(py::reinterpret_borrow<py::object>(h));
    if (!points.is_none())
      for (py::handle h : py::iter(points)) clouds.push_back(py::reinterpret_borrow<py::object>(h));
    if (gts.size() != preds.size())
      throw py::value_error("pred holds " + std::to_string(preds.size()) + " frames, gt_labels " +
                            std::to_string(gts.size()));
    if (!points.is_none() && clouds.size() != preds.size())
      throw py::value_error("pred holds " + std::to_string(preds.size()) + " frames, points " +
                            std::to_string(clouds.size()));
  } else {
    preds.push_back(py::reinterpret_borrow<py::object>(pred));
    gts.push_back(py::reinterpret_borrow<py::object>(gt));
    if (!points.is_none()) clouds.push_back(py::reinterpret_borrow<py::object>(points));
  }
  if (protocol == Protocol::kPW && clouds.empty())
    throw py::value_error("protocol pw needs each point's z: give points=");
  if (by_range && clouds.empty())
    throw py::value_error("by_range needs each point's x and y: give points=");

  SequenceScores totals(protocol);
  std::optional<ClassBreakdown> classes;
  std::optional<RangeBreakdown> ranges;
  if (by_class) classes.emplace(std::vector<Protocol>{protocol});
  if (by_range) ranges.emplace(std::vector<Protocol>{protocol});
  py::list per_frame;
  for (size_t f = 0; f < preds.size(); ++f) {
    const std::string at = sequence ? "[" + std::to_string(f) + "]" : "";
    const std::vector<uint32_t> truth = ToUint32(gts[f], "gt_labels" + at, 0, false);
    const Labels predicted = ToPrediction(preds[f], "pred" + at, truth.size());
    Cloud cloud;
    std::vector<float> z;
    if (!clouds.empty()) cloud = PointsOf(clouds[f], "points" + at, truth.size());
    for (size_t i = 0; i < cloud.size(); ++i) z.push_back(cloud.z(i));
    const std::vector<float>* zp = clouds.empty() ? nullptr : &z;
    const Scores s = totals.Add(CountFrame(protocol, predicted, truth, zp));
    per_frame.append(ScoresDict(s));
    if (classes) classes->Add(predicted, truth, zp);
    if (ranges) ranges->Add(cloud, predicted, truth);
  }
  py::dict result = ScoresDict(totals.Total());
  AddCounts(totals.summed(), result);
  result["frames"] = totals.frames();
  result["protocol"] = ProtocolName(protocol);
  result["ontology"] = OntologyName(ontology);
  if (sequence) result["per_frame"] = per_frame;
  if (classes) result["by_class"] = ByClassList(*classes, ontology);
  if (ranges) result["by_range"] = ByRangeList(*ranges);
  return result;
}

SceneKind ParseScene(const std::string& name) {
  if (name == "urban") return kUrban;
  if (name == "flat") return kFlat;
  if (name == "flat-objects") return kFlatWithObjects;
  throw py::value_error("scene must be urban, flat or flat-objects, not '" + name + "'");
}

py::tuple SimulatePy(py::handle sensor, long long seed, double pitch, double roll,
                     const std::string& scene, double range_noise, bool rings,
                     bool reflection_noise) {
  if (seed < 0 || seed > 0xFFFFFFFFll)
    throw py::value_error("seed must lie in [0, 4294967295], not " + std::to_string(seed));
  for (const auto& [name, deg] : {std::pair{"pitch", pitch}, std::pair{"roll", roll}})
    if (!std::isfinite(deg) || std::abs(deg) > 30.0)
      throw py::value_error(std::string(name) + " must lie within [-30, 30] degrees");
  if (!(range_noise >= 0.0 && range_noise <= 1.0))
    throw py::value_error("range_noise must lie within [0, 1] m");
  SimOptions options;
  options.seed = uint32_t(seed);
  options.pitch_deg = float(pitch);
  options.roll_deg = float(roll);
  options.kind = ParseScene(scene);
  options.range_noise_m = float(range_noise);
  options.emit_rings = rings;
  options.reflection_noise = reflection_noise;
  const std::string name_or_path = PathArg(sensor);
  const std::string sensors_dir = SensorsDir();
  SimScan scan;
  {
    py::gil_scoped_release nogil;
    scan = Simulate(LoadSensorProfile(name_or_path, sensors_dir), options);
  }
  py::array labels = VectorArray(std::move(scan.labels));
  return py::make_tuple(CloudArray(std::move(scan.cloud)), labels);
}

std::vector<std::string> DevicesPy() {
  vk::Result<vk::Instance> instance = vk::Instance::Create({});
  if (!instance.ok()) return {};
  vk::Result<std::vector<std::string>> lines = vk::Device::Describe(instance.value());
  return lines.ok() ? lines.value() : std::vector<std::string>{};
}

}  // namespace

void BindFunctions(py::module_& m) {
  m.def("read_cloud", &ReadCloudPy, py::arg("path"), py::kw_only(),
        py::arg("nuscenes") = py::none(), py::arg("ring") = false,
        R"doc(read_cloud(path, *, nuscenes=None, ring=False)
--

Reads a scan in any format the command line reads.

Formats by extension: .bin (KITTI's 4 float32 a point; files named *.pcd.bin as nuScenes' 5),
.pcd (ASCII, binary or binary_compressed), .ply (ASCII or binary little-endian). A .pcd or .ply
field named intensity, scalar_intensity, reflectivity, remission or i (in any case; the first of
these when several) is the intensity; a file with none reads intensity 0 and warns (UserWarning).

Args:
    path: the file (str or os.PathLike).
    nuscenes: True reads any .bin as nuScenes' 5 floats (x, y, z, intensity, ring), False as
        KITTI's 4; None decides by the name, as the command line does.
    ring: also return the file's ring field.

Returns:
    (N, 4) float32 x, y, z, intensity, without a copy: the array owns what the reader read. It
    carries the file's ring field (nuScenes, PLY and PCD files with a ring) to Segmenter.segment
    as long as it is passed whole. With ring=True the tuple (points, ring), ring (N,) int32 or
    None when the file has none.

Raises:
    OSError: a missing, unreadable, truncated or malformed file, or an unknown extension; the
        message names the file and the problem.)doc");
  m.def("read_labels", &ReadLabelsPy, py::arg("path"), py::arg("expected_points") = 0,
        R"doc(read_labels(path, expected_points=0)
--

Reads a SemanticKITTI .label file (or a prediction lpir-gseg wrote).

Returns:
    (N,) uint32: class = value & 0xFFFF, instance = value >> 16 (a prediction: 1 ground, 0 not).

Raises:
    OSError: a missing or empty file, a size not a whole number of labels, or, when
        expected_points > 0, another count (the message gives both).)doc");
  m.def("write_labels", &WriteLabelsPy, py::arg("path"), py::arg("labels"),
        R"doc(write_labels(path, labels)
--

Writes labels as a .label file, one little-endian uint32 a point: the bytes
`lpir-gseg segment` writes for the same labels.

Args:
    path: the file to write.
    labels: (N,) integers or bools in [0, 2**32).)doc");
  m.def(
      "evaluate", &EvaluatePy, py::arg("pred"), py::arg("gt_labels"),
      py::arg("protocol") = py::none(), py::arg("ontology") = "semantickitti", py::kw_only(),
      py::arg("points") = py::none(), py::arg("by_class") = false, py::arg("by_range") = false,
      R"doc(evaluate(pred, gt_labels, protocol=None, ontology="semantickitti", *, points=None, by_class=False, by_range=False)
--

Scores predictions against ground-truth labels, as `lpir-gseg evaluate` does.

Args:
    pred: (N,) labels (any non-zero value is ground), or a list of them, one a frame.
    gt_labels: (N,) stored labels of the ontology (read_labels), or a list of them.
    protocol: "dg" (DipG-Seg's evaluator, the default for semantickitti), "pp", "pw", "gg", or
        "rellis" (the only one, and the default, for rellis3d). See host/eval/metrics.h.
    ontology: "semantickitti" or "rellis3d".
    points: (N, 3 or 4) points (or a list), needed by "pw", which reads each point's z, and by
        by_range, which reads x and y.
    by_class: also the outcome per ground-truth class.
    by_range: also the outcome per band of horizontal range sqrt(x^2 + y^2).

Returns:
    A dict: precision, recall, f1, iou (fractions in [0, 1]; a ratio over 0 is 0), the summed
    counts tp, fp, fn, tn, ignored, frames, protocol and ontology; for a list also per_frame, the
    scores of each frame. dg, gg and rellis score the summed counts, pp and pw average the
    per-frame scores. With by_class, "by_class": a dict per class present, ascending (class,
    name, points, predicted_ground, share, tp, fp, fn, tn, ignored); with by_range, "by_range":
    a dict per band 0-5, 5-10, 10-20, 20-30, 30-40, 40-60, 60+ m (band, from, to (None for the
    last), points, tp, fp, fn, tn, ignored): the figures of `lpir-gseg evaluate --by-class
    --by-range --json`, point counts summed over the frames.

Raises:
    ValueError: an unknown protocol or ontology, lengths that do not match, or "pw" or by_range
        without points.)doc");
  m.def(
      "simulate", &SimulatePy, py::arg("sensor"), py::arg("seed"), py::kw_only(),
      py::arg("pitch") = 0.0, py::arg("roll") = 0.0, py::arg("scene") = "urban",
      py::arg("range_noise") = 0.02, py::arg("rings") = false, py::arg("reflection_noise") = true,
      R"doc(simulate(sensor, seed, *, pitch=0.0, roll=0.0, scene="urban", range_noise=0.02, rings=False, reflection_noise=True)
--

One scan of the synthetic street (or a flat scene) seen by a sensor, as
`lpir-gseg simulate` makes it: deterministic for the same arguments.

Args:
    sensor: a profile name or a profile file.
    seed: 0 to 2**32 - 1; draws the street's layout and the noise.
    pitch, roll: mount tilt in degrees, |angle| <= 30: positive pitch makes the ground rise
        ahead (+x), positive roll to the left (+y) (apps/sim/scene.h).
    scene: "urban", "flat" (one road plane) or "flat-objects" (the plane, a car and a wall).
    range_noise: sigma of the Gaussian range noise, metres, in [0, 1].
    rings: fill the points' ring field (segment then reads it).
    reflection_noise: a few multipath points 0.5-2 m under the road (class 1).

Returns:
    (points, labels): (N, 4) float32 as read_cloud returns them, and (N,) uint32 SemanticKITTI
    classes (ground: 40, 44, 48, 49, 60, 72).)doc");
  m.def(
      "sensors", [] { return KnownSensorProfiles(SensorsDir()); },
      "sensors()\n--\n\nThe names of the sensor profiles shipped with the package, sorted.");
  m.def("sensors_dir", &SensorsDir,
        "sensors_dir()\n--\n\nThe folder the shipped sensor profiles are in.");
  m.def("devices", &DevicesPy,
        R"doc(devices()
--

The Vulkan devices of this machine, one line each as `lpir-gseg devices` prints
them: index, name, type, API version, and "usable" or why not. Empty when there is no Vulkan
driver at all.)doc");
  m.def(
      "_output_paths",
      [](const std::vector<std::tuple<std::string, std::string, bool>>& inputs, py::handle out_dir,
         const std::string& extension) {
        std::vector<RunInput> runs;
        for (const auto& [path, folder, drive] : inputs) runs.push_back({path, folder, drive});
        return OutputPaths(runs, PathArg(out_dir), extension);
      },
      py::arg("inputs"), py::arg("out_dir"), py::arg("extension"),
      R"doc(_output_paths(inputs, out_dir, extension)
--

Where each input of a run writes (host/io/output_paths.h), the rule `lpir-gseg segment` follows:
out_dir joined with the input's path below the folder it was listed from (its file name when
given itself), the extension replaced by `extension` (a drive's: its own folder).

Args:
    inputs: (path, folder, drive) per input: folder "" when the input was given itself; drive
        True for a recorded drive.

Raises:
    ValueError: two inputs would write one output (both named), an input listed twice, or an
        output that is an input.)doc");
  m.def(
      "is_cloud_file", [](py::handle path) { return IsCloudFile(PathArg(path)); }, py::arg("path"),
      "is_cloud_file(path)\n--\n\nTrue for the extensions read_cloud reads (cloud_formats()): how "
      "a folder is listed.");
  m.def(
      "cloud_formats",
      [] {
        std::vector<std::string> extensions;
        for (const CloudFormat& f : CloudFormats())
          extensions.push_back("." + std::string(f.extension));
        return extensions;
      },
      "cloud_formats()\n--\n\nThe extensions of the cloud files read_cloud reads, as the command "
      "line's help lists them: ['.bin', '.pcd', '.ply'] (host/io/cloud_file.h, one row a format).");
}

}  // namespace lpir::python
