// NumPy arrays in and out of the library's types (see arrays.h).
#include "arrays.h"

#include <cstring>
#include <limits>
#include <string>

namespace lpir::python {
namespace {

// The name of the capsules that own a Cloud: how OwnedCloud knows one of its own.
constexpr const char* kCloudCapsule = "lpir_gseg.Cloud";

std::string ShapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string DtypeText(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// `h` as an array (a list of numbers becomes one); ValueError naming `name` when NumPy cannot.
py::array AsArray(py::handle h, const std::string& name) {
  if (h.is_none()) throw py::value_error(name + " is None, not an array");
  py::array a = py::array::ensure(h);
  if (!a)
    throw py::value_error(name + " is not an array (a " + std::string(Py_TYPE(h.ptr())->tp_name) +
                          ")");
  return a;
}

void RequireNumbers(const py::array& a, const std::string& name) {
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::value_error(name + " must hold real numbers (float or int), not dtype " +
                          DtypeText(a));
}

// A 1-D array of `n` numbers (n > 0 required), as float32 in C order.
py::array_t<float, py::array::c_style> FloatColumn(py::handle h, const std::string& name,
                                                   size_t n) {
  py::array a = AsArray(h, name);
  RequireNumbers(a, name);
  if (a.ndim() != 1 || size_t(a.shape(0)) != n)
    throw py::value_error(name + " must have shape (" + std::to_string(n) + ",), one value a " +
                          "point, not " + ShapeText(a));
  return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
}

// A 1-D array of integers (bool too when `allow_bool`) in [lo, hi], converted to Out.
template <typename Out>
std::vector<Out> IntegerVector(py::handle values, const std::string& name, size_t expected,
                               bool allow_bool, int64_t lo, int64_t hi) {
  py::array a = AsArray(values, name);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && !(allow_bool && kind == 'b'))
    throw py::value_error(name + " must hold integers" + (allow_bool ? " or bools" : "") +
                          ", not dtype " + DtypeText(a));
  if (a.ndim() != 1)
    throw py::value_error(name + " must be one-dimensional, not shape " + ShapeText(a));
  const size_t n = size_t(a.shape(0));
  if (expected > 0 && n != expected)
    throw py::value_error(name + " has " + std::to_string(n) + " values for " +
                          std::to_string(expected) + " points");
  std::vector<Out> out(n);
  auto out_of_range = [&](size_t i, const std::string& value) {
    return py::value_error(name + "[" + std::to_string(i) + "] is " + value + ", outside [" +
                           std::to_string(lo) + ", " + std::to_string(hi) + "]");
  };
  if (kind == 'u' && a.itemsize() == 8) {  // above int64's range: read as unsigned
    auto u = py::array_t<uint64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    const uint64_t* p = u.data();
    for (size_t i = 0; i < n; ++i) {
      if (p[i] > uint64_t(hi)) throw out_of_range(i, std::to_string(p[i]));
      out[i] = Out(p[i]);
    }
  } else {
    auto s = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    const int64_t* p = s.data();
    for (size_t i = 0; i < n; ++i) {
      if (p[i] < lo || p[i] > hi) throw out_of_range(i, std::to_string(p[i]));
      out[i] = Out(p[i]);
    }
  }
  return out;
}

}  // namespace

py::array CloudArray(Cloud&& cloud) {
  auto* owned = new Cloud(std::move(cloud));
  py::capsule owner(owned, kCloudCapsule, [](PyObject* capsule) {
    delete static_cast<Cloud*>(PyCapsule_GetPointer(capsule, kCloudCapsule));
  });
  const py::ssize_t n = py::ssize_t(owned->size());
  return py::array_t<float>({n, py::ssize_t(4)},
                            {py::ssize_t(4 * sizeof(float)), py::ssize_t(sizeof(float))},
                            owned->xyzi.data(), owner);
}

const Cloud* OwnedCloud(const py::array& points) {
  py::object base = points.base();
  while (base && py::isinstance<py::array>(base))
    base = py::reinterpret_borrow<py::array>(base).base();
  if (!base || !PyCapsule_IsValid(base.ptr(), kCloudCapsule)) return nullptr;
  const auto* cloud = static_cast<const Cloud*>(PyCapsule_GetPointer(base.ptr(), kCloudCapsule));
  const bool whole = points.ndim() == 2 && size_t(points.shape(0)) == cloud->size() &&
                     points.shape(1) == 4 && points.data() == cloud->xyzi.data() &&
                     points.dtype().is(py::dtype::of<float>()) &&
                     (points.flags() & py::array::c_style);
  return whole ? cloud : nullptr;
}

CloudView ToCloud(py::handle points, py::handle intensity, py::handle ring, const std::string& name,
                  Cloud* scratch) {
  CloudView view;
  view.keep = AsArray(points, name);
  const py::array& a = view.keep;
  RequireNumbers(a, name);
  if (a.ndim() != 2 || (a.shape(1) != 3 && a.shape(1) != 4))
    throw py::value_error(name + " must have shape (N, 4) (x, y, z, intensity) or (N, 3), not " +
                          ShapeText(a));
  const size_t n = size_t(a.shape(0)), columns = size_t(a.shape(1));
  const bool has_intensity = !intensity.is_none();
  if (columns == 4 && has_intensity)
    throw py::value_error(name + " has 4 columns, intensity among them: intensity= is for " +
                          "(N, 3) points");
  if (columns == 4 && ring.is_none()) {
    if (const Cloud* own = OwnedCloud(a)) {
      view.cloud = own;
      return view;
    }
  }
  scratch->xyzi.resize(4 * n);
  float* xyzi = scratch->xyzi.data();
  if (columns == 4 && a.dtype().is(py::dtype::of<float>()) && (a.flags() & py::array::c_style)) {
    if (n) std::memcpy(xyzi, a.data(), 4 * n * sizeof(float));
  } else {
    auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!f) throw py::error_already_set();
    const float* p = f.data();
    for (size_t i = 0; i < n; ++i) {
      for (size_t c = 0; c < columns; ++c) xyzi[4 * i + c] = p[columns * i + c];
      if (columns == 3) xyzi[4 * i + 3] = 0.0f;  // (N, 3) without intensity=: 0, never read
    }
  }
  if (has_intensity) {
    const auto column = FloatColumn(intensity, "intensity", n);
    const float* p = column.data();
    for (size_t i = 0; i < n; ++i) xyzi[4 * i + 3] = p[i];
  }
  if (ring.is_none()) {
    scratch->ring.clear();
  } else {
    scratch->ring =
        IntegerVector<int32_t>(ring, "ring", n, false, std::numeric_limits<int32_t>::min(),
                               std::numeric_limits<int32_t>::max());
  }
  view.cloud = scratch;
  return view;
}

std::vector<uint32_t> ToUint32(py::handle values, const std::string& name, size_t expected,
                               bool allow_bool) {
  return IntegerVector<uint32_t>(values, name, expected, allow_bool, 0,
                                 std::numeric_limits<uint32_t>::max());
}

std::string PathArg(py::handle obj) {
  const std::string path = py::module_::import("os").attr("fsdecode")(obj).cast<std::string>();
  if (path.empty()) throw py::value_error("the path is empty");
  if (path.find('\0') != std::string::npos)
    throw py::value_error("the path '" + path.substr(0, path.find('\0')) + "...' holds a NUL");
  return path;
}

}  // namespace lpir::python
