// lpir_gseg.Segmenter: lpir::Segmenter (host/api/segmenter.h) for NumPy arrays. Every call releases
// the GIL while the library works and takes the object's mutex first (with the GIL released, so
// two threads sharing one segmenter wait on each other, never deadlock); only the conversion of
// the input and the allocation of the output hold the GIL.
#include "host/api/segmenter.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "host/api/sensor_fit.h"
#include "host/io/sensor_profile.h"

namespace lpir::python {
namespace {

constexpr char kVulkanNotePrefix[] = "Vulkan on ";

// One frame's output arrays, allocated with the GIL, written without it.
struct Output {
  py::array_t<uint8_t> label, why;
  uint8_t* label_data = nullptr;
  uint8_t* why_data = nullptr;

  Output(size_t n, bool with_why) : label(py::ssize_t(n)) {
    label_data = label.mutable_data();
    if (with_why) why = py::array_t<uint8_t>(py::ssize_t(n)), why_data = why.mutable_data();
  }
  void Fill(const Frame& frame) {
    if (frame.n) std::memcpy(label_data, frame.label.data(), frame.n);
    if (why_data && frame.n) std::memcpy(why_data, frame.why.data(), frame.n);
  }
  py::object Result() const {
    if (!why_data) return label;
    return py::make_tuple(label, why);
  }
};

// params= as ApplySettings takes them: (name, value as text), in the mapping's order. A whole
// number (int, numpy integer) is its digits, any other real number Python's repr of it as a
// float, a str as it is; bools and other types are a TypeError naming the key.
std::vector<std::pair<std::string, std::string>> SettingsArg(py::handle params) {
  std::vector<std::pair<std::string, std::string>> settings;
  if (params.is_none()) return settings;
  if (!py::isinstance<py::dict>(params) && !py::hasattr(params, "items"))
    throw py::type_error("params must be a dict of setting names and values, or None");
  for (py::handle item : params.attr("items")()) {
    const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
    if (!py::isinstance<py::str>(pair[0]))
      throw py::type_error("params: the names must be str, not " +
                           py::repr(pair[0]).cast<std::string>());
    const std::string name = pair[0].cast<std::string>();
    const py::handle value = pair[1];
    std::string text;
    if (py::isinstance<py::str>(value)) {
      text = value.cast<std::string>();
    } else if (!py::isinstance<py::bool_>(value) && PyIndex_Check(value.ptr())) {
      text = py::str(py::int_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
    } else if (!py::isinstance<py::bool_>(value) && PyNumber_Check(value.ptr())) {
      text = py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
    } else {
      throw py::type_error("params['" + name + "'] must be a number or a str, not " +
                           py::repr(value).cast<std::string>());
    }
    settings.emplace_back(name, text);
  }
  return settings;
}

// Each of `warnings` (host/api/sensor_fit.h: the cloud does not look like the profile's sensor) as
// a Python UserWarning naming `what`; a warning turned into an error by the warnings filter raises.
void Warn(const std::vector<std::string>& warnings, const std::string& what) {
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, (what + ": " + w).c_str(), 1) < 0)
      throw py::error_already_set();
}

class PySegmenter {
 public:
  PySegmenter(py::handle sensor, const std::string& backend, py::handle device,
              py::handle max_points, uint32_t frames_in_flight, uint32_t batch, bool validation,
              py::handle params, py::handle threads) {
    SegmenterOptions options;
    options.backend = ParseBackend(backend);
    if (!device.is_none()) {
      if (py::isinstance<py::bool_>(device) ||
          !(py::isinstance<py::str>(device) || py::isinstance<py::int_>(device)))
        throw py::type_error("device must be a name, an index or None");
      options.device = py::str(device).cast<std::string>();
      if (py::isinstance<py::int_>(device) && device.cast<long long>() < 0)
        throw py::value_error("device index " + options.device + " is negative");
    }
    if (!max_points.is_none()) {
      if (py::isinstance<py::bool_>(max_points) || !py::isinstance<py::int_>(max_points))
        throw py::type_error("max_points must be an int or None");
      const long long value = max_points.cast<long long>();
      if (value < 1)
        throw py::value_error("max_points must be at least 1, not " + std::to_string(value));
      options.max_points = size_t(value);
    }
    if (frames_in_flight < 1) throw py::value_error("frames_in_flight must be at least 1");
    if (batch < 1 || batch > 64) throw py::value_error("batch must be between 1 and 64");
    options.frames_in_flight = frames_in_flight;
    options.batch = batch;
    options.validation = validation;
    if (!threads.is_none()) {
      if (py::isinstance<py::bool_>(threads) || !py::isinstance<py::int_>(threads))
        throw py::type_error("threads must be an int or None");
      const long long value = threads.cast<long long>();
      if (value < 1 || value > 1024)
        throw py::value_error("threads must be from 1 to 1024, not " + std::to_string(value));
      options.threads = uint32_t(value);
    }
    const std::string name_or_path = PathArg(sensor);
    const std::string sensors_dir = SensorsDir();
    const std::vector<std::pair<std::string, std::string>> settings = SettingsArg(params);
    py::gil_scoped_release nogil;  // a Vulkan set-up compiles pipelines: seconds on lavapipe
    SensorProfile profile = LoadSensorProfile(name_or_path, sensors_dir);
    try {
      ApplySettings(profile, settings);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("params: ") + e.what());
    }
    segmenter_ = std::make_unique<Segmenter>(profile, options);
  }

  py::object Segment(py::handle points, py::handle intensity, py::handle ring, bool why) {
    CloudView view;  // destroyed after the GIL is back, as every Python object here
    std::unique_ptr<Output> out;
    std::vector<std::string> misfit;
    {
      py::gil_scoped_release nogil;
      std::lock_guard<std::mutex> lock(mutex_);
      {
        py::gil_scoped_acquire gil;
        view = ToCloud(points, intensity, ring, "points", &scratch_);
        CheckSize(*view.cloud, "points");
        out = std::make_unique<Output>(view.cloud->size(), why);
      }
      out->Fill(segmenter_->Segment(*view.cloud));
      misfit = SensorFitWarnings(MeasureSensorFit(*view.cloud, segmenter_->sensor()),
                                 segmenter_->sensor());
    }
    Warn(misfit, "points");
    return out->Result();
  }

  py::list SegmentBatch(py::handle clouds, bool why) {
    std::vector<py::object> items;
    for (py::handle item : py::iter(clouds))
      items.push_back(py::reinterpret_borrow<py::object>(item));
    std::vector<std::unique_ptr<Output>> outputs(items.size());
    {
      py::gil_scoped_release nogil;
      std::lock_guard<std::mutex> lock(mutex_);
      std::deque<size_t> pending;  // item indices, oldest first
      size_t at = 0;               // the item the current step works on
      auto collect = [&] {
        at = pending.front();
        outputs[at]->Fill(segmenter_->Collect());
        pending.pop_front();
      };
      try {
        for (size_t i = 0; i < items.size(); ++i) {
          const Cloud* cloud = nullptr;
          {
            py::gil_scoped_acquire gil;
            at = i;
            const std::string name = "clouds[" + std::to_string(i) + "]";
            CloudView view = ToCloud(items[i], py::none(), py::none(), name, &scratch_);
            CheckSize(*view.cloud, name);
            cloud = view.cloud;  // scratch_, or the cloud items[i] owns
            outputs[i] = std::make_unique<Output>(cloud->size(), why);
            Warn(SensorFitWarnings(MeasureSensorFit(*cloud, segmenter_->sensor()),
                                   segmenter_->sensor()),
                 name);
          }
          while (!segmenter_->CanSubmit()) collect();
          at = i;
          segmenter_->Submit(*cloud);  // copies the cloud: scratch_ is free for the next item
          pending.push_back(i);
        }
        while (!pending.empty()) collect();
      } catch (const py::error_already_set&) {
        Drain();
        throw;
      } catch (const py::builtin_exception&) {  // names the item already
        Drain();
        throw;
      } catch (const std::invalid_argument& e) {
        Drain();
        throw py::value_error("clouds[" + std::to_string(at) + "]: " + e.what());
      } catch (const std::length_error& e) {
        Drain();
        throw py::value_error("clouds[" + std::to_string(at) + "]: " + e.what());
      } catch (const std::exception& e) {
        Drain();
        throw std::runtime_error("clouds[" + std::to_string(at) + "]: " + e.what());
      }
    }
    py::list result;
    for (const auto& out : outputs) result.append(out->Result());
    return result;
  }

  std::string backend() const {
    return segmenter_->backend() == Backend::kVulkan ? "vulkan" : "cpu";
  }
  py::object device() const {
    const std::string& note = segmenter_->backend_note();
    if (segmenter_->backend() != Backend::kVulkan || note.rfind(kVulkanNotePrefix, 0) != 0)
      return py::none();
    return py::str(note.substr(sizeof(kVulkanNotePrefix) - 1));
  }
  const std::string& backend_note() const { return segmenter_->backend_note(); }
  const std::string& sensor() const { return segmenter_->sensor().name; }
  size_t max_points() const { return segmenter_->max_points(); }
  size_t frames_in_flight() const { return segmenter_->frames_in_flight(); }
  uint32_t threads() const { return segmenter_->threads(); }
  bool on_cpu_driver() const { return segmenter_->on_cpu_driver(); }
  py::dict mount() {
    std::lock_guard<std::mutex> lock(mutex_);
    const MountEstimate& m = segmenter_->mount();
    py::dict d;
    d["sensor_height"] = double(m.mount.sensor_height);
    d["k_xz"] = double(m.mount.k_xz);
    d["k_yz"] = double(m.mount.k_yz);
    d["estimated"] = m.estimated;
    return d;
  }

 private:
  void CheckSize(const Cloud& cloud, const std::string& name) const {
    if (cloud.size() > segmenter_->max_points())
      throw py::value_error(name + " has " + std::to_string(cloud.size()) +
                            " points, more than the segmenter's max_points of " +
                            std::to_string(segmenter_->max_points()) +
                            " (Segmenter(..., max_points=N) raises it)");
  }
  // Collects and drops every pending frame, so that the segmenter takes the next call; bounded
  // (a Collect that fails before taking its frame would otherwise repeat).
  void Drain() {
    for (size_t tries = segmenter_->pending(); tries > 0 && segmenter_->pending() > 0; --tries) {
      try {
        segmenter_->Collect();
      } catch (const std::exception&) {
      }
    }
  }

  std::unique_ptr<Segmenter> segmenter_;
  std::mutex mutex_;
  Cloud scratch_;  // the last copied input, its vectors reused from call to call
};

const char kSegmenterDoc[] =
    R"doc(Segmenter(sensor="hdl64e", backend="auto", device=None, max_points=None, frames_in_flight=2, batch=1, validation=False, params=None, threads=None)

Labels LiDAR scans ground or non-ground, one sensor's scans.

Made once per sensor (its tables and, on Vulkan, every device buffer are allocated here, for
max_points points) and used for every scan. Both backends give the same bytes.

Args:
    sensor: a profile name (lpir_gseg.sensors() lists them) or the path of a profile file.
    backend: "auto" (Vulkan on a GPU, else the CPU reference; backend_note says why), "cpu"
        (the reference), or "vulkan" (any usable device, CPU drivers such as lavapipe included,
        or an error).
    device: a Vulkan device: its index, or a part of its name (lpir_gseg.devices() lists them).
        A named device may be a CPU driver. None: the first usable one.
    max_points: the largest scan taken; None: the profile's max_points, else beams x width x 2.
    frames_in_flight: frames segment_batch keeps on the device at once.
    batch: Vulkan: frames recorded in one command buffer by segment_batch (offline relabelling).
    validation: the Vulkan validation layer (messages on stderr).
    params: settings changed for this segmenter, as `lpir-gseg segment --set NAME=VALUE` changes
        them: {"sensor_height": 1.9, "h_athr": 0.15}. A name is one of the profile's keys
        sensor_height, min_range, max_range, k_xz, k_yz, ring_zero_is_top, max_points, mount
        ("fixed" or "per_frame"), or a parameter of reference_cpu/params.cpp; each value is
        checked as the profile line `NAME VALUE` or `param NAME VALUE` would be.
    threads: the CPU backend's threads (1 to 1024); None: every core this process may run on
        (its affinity). A scan segmented alone runs on all of them; segment_batch's frames in
        flight run side by side, threads / frames_in_flight each. The labels are the same at any
        count; 1 runs the reference on the calling thread. Ignored on Vulkan.

Raises:
    ValueError: an unknown sensor name, backend or bad option; in params an unknown name (the
        message names the nearest known one) or a value it does not take.
    TypeError: params not a dict, or a value that is neither a number nor a str.
    FileNotFoundError: a profile path (holding a '/') to a file that does not exist.
    OSError: a malformed profile file (the message names the file and line).
    RuntimeError: backend="vulkan" (or a device named) and no device could be set up.

A segmenter may be shared between threads: calls wait for each other, and the GIL is released
while a scan is segmented, so other Python threads run meanwhile.)doc";

const char kSegmentDoc[] = R"doc(segment(self, points, *, intensity=None, ring=None, why=False)
--

Labels one scan.

Args:
    points: (N, 4) x, y, z (metres, sensor frame) and intensity, in any unit (the labels do not
        read it); or (N, 3) x, y, z, with or without intensity=. Any float or int dtype. A C-contiguous float32 (N, 4) array is read as it
        is (one copy into the segmenter's reused buffer, no NumPy conversion); an array that
        read_cloud or simulate returned, unsliced, is read in place, ring field and all.
    intensity: (N,) intensities, with (N, 3) points only (not read by the method).
    ring: (N,) laser index of each point as the file numbers it (the profile's ring_zero_is_top
        says which end 0 is), or None: the row is found from the elevation. An array from
        read_cloud brings the file's own ring field without this argument.
    why: also return the reason codes.

Returns:
    (N,) uint8 labels, 1 ground and 0 non-ground; with why=True the tuple (labels, why), why
    (N,) uint8: WHY_NON_GROUND, WHY_GROUND, WHY_INVALID (NaN/Inf coordinates, at the origin,
    out of range, a ring outside the beams) or WHY_NOISE (reflection noise below the ground).

Warns:
    UserWarning: the cloud does not look like the profile's sensor: a few rings outside the
        beams, or points more than 2 degrees outside the beam table (wrong sensor, or a tilt).

Raises:
    ValueError: a wrong shape, dtype or length, more points than max_points, or rings outside
        the profile's beams on more than 1 % of the points (wrong sensor).
    RuntimeError: the device failed.)doc";

const char kSegmentBatchDoc[] = R"doc(segment_batch(self, clouds, *, why=False)
--

Labels several scans, keeping frames_in_flight of them on the device at once (on Vulkan the
next scan is uploaded while the device works on the previous ones; with batch > 1 they are
recorded together). The CPU backend labels them one after the other.

Args:
    clouds: an iterable of (N_i, 4) arrays, as segment takes them (read_cloud's arrays keep their
        ring field).
    why: each result is the tuple (labels, why).

Returns:
    A list with one result per scan, in order, as segment returns it.

Raises:
    ValueError, RuntimeError: as segment; the message starts with clouds[i], the scan at fault.
    The scans before it were labelled but are not returned.)doc";

}  // namespace

void BindSegmenter(py::module_& m) {
  py::class_<PySegmenter>(m, "Segmenter", kSegmenterDoc)
      .def(py::init<py::handle, const std::string&, py::handle, py::handle, uint32_t, uint32_t,
                    bool, py::handle, py::handle>(),
           "__init__(self, sensor=\"hdl64e\", backend=\"auto\", device=None, max_points=None, "
           "frames_in_flight=2, batch=1, validation=False, params=None, threads=None)\n--\n\nSee "
           "the class's "
           "docstring.",
           py::arg("sensor") = "hdl64e", py::arg("backend") = "auto",
           py::arg("device") = py::none(), py::arg("max_points") = py::none(),
           py::arg("frames_in_flight") = 2, py::arg("batch") = 1, py::arg("validation") = false,
           py::arg("params") = py::none(), py::arg("threads") = py::none())
      .def("segment", &PySegmenter::Segment, kSegmentDoc, py::arg("points"), py::kw_only(),
           py::arg("intensity") = py::none(), py::arg("ring") = py::none(), py::arg("why") = false)
      .def("segment_batch", &PySegmenter::SegmentBatch, kSegmentBatchDoc, py::arg("clouds"),
           py::kw_only(), py::arg("why") = false)
      .def_property_readonly("backend", &PySegmenter::backend,
                             "The backend in use: \"vulkan\" or \"cpu\" (never \"auto\").")
      .def_property_readonly("device", &PySegmenter::device,
                             "The Vulkan device's name, or None on the CPU reference.")
      .def_property_readonly("backend_note", &PySegmenter::backend_note,
                             "One line saying which backend runs and why, e.g. \"CPU "
                             "reference, no Vulkan device: ...\".")
      .def_property_readonly("sensor", &PySegmenter::sensor, "The profile's name.")
      .def_property_readonly("max_points", &PySegmenter::max_points,
                             "The largest scan this segmenter takes.")
      .def_property_readonly("frames_in_flight", &PySegmenter::frames_in_flight,
                             "The most frames segment_batch keeps pending (frames_in_flight x "
                             "batch as constructed).")
      .def_property_readonly("threads", &PySegmenter::threads,
                             "The CPU backend's threads (None resolved to the cores this process "
                             "may run on); 1 on Vulkan.")
      .def_property_readonly("on_cpu_driver", &PySegmenter::on_cpu_driver,
                             "True when the Vulkan device is a CPU driver (lavapipe).")
      .def_property_readonly(
          "mount", &PySegmenter::mount,
          "The mount the last cloud was segmented with (for segment_batch, the last of the "
          "batch): {\"sensor_height\": m, \"k_xz\": ..., \"k_yz\": ..., \"estimated\": bool}, "
          "estimated True when it is that cloud's own estimate (profile key mount per_frame), "
          "False when it is the profile's (mount fixed, or a cloud showing too little ground).")
      .def("__repr__", [](const PySegmenter& s) {
        return "<lpir_gseg.Segmenter sensor='" + s.sensor() + "' backend='" + s.backend() +
               "': " + s.backend_note() + ">";
      });
}

}  // namespace lpir::python
