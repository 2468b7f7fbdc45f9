// NumPy arrays in and out of the library's types. Arrays handed out own the vector they view (a
// capsule holds it): nothing is copied. Arrays taken in are checked (dimensions, length, dtype
// kind) and every problem is a ValueError naming the argument; their numbers are converted to the
// library's types as NumPy's astype would.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"

namespace lpir::python {

namespace py = pybind11;

// An (N, 4) float32 array over cloud.xyzi that owns the whole cloud, its ring field included.
py::array CloudArray(Cloud&& cloud);
// The cloud behind `points` when it is an array CloudArray made, viewed whole (same first float,
// shape (N, 4), C order, float32); else null. A segmenter reads such a cloud in place, ring and
// all: the path by which read_cloud's arrays give the labels the command line gives.
const Cloud* OwnedCloud(const py::array& points);

// An (N,) array that owns `values`.
template <typename T>
py::array VectorArray(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({owned->size()}, {sizeof(T)}, owned->data(), owner);
}

// Points as the segmenter takes them. `points` is (N, 4) (x, y, z, intensity), or (N, 3) with
// `intensity` (N,); `ring` (N,) integers or None. Floats and integers of any width are taken;
// `name` ("points", "clouds[2]") starts every error message.
struct CloudView {
  const Cloud* cloud = nullptr;  // *scratch, or the array's own cloud (OwnedCloud)
  py::array keep;                // the input array, alive while the cloud is read
};
CloudView ToCloud(py::handle points, py::handle intensity, py::handle ring, const std::string& name,
                  Cloud* scratch);

// A 1-D array of integers (bool included when `allow_bool`) as uint32, each in [0, 2^32);
// `expected` > 0 requires that length.
std::vector<uint32_t> ToUint32(py::handle values, const std::string& name, size_t expected,
                               bool allow_bool);

// `obj` as a filesystem path: str, bytes or os.PathLike (TypeError otherwise).
std::string PathArg(py::handle obj);

}  // namespace lpir::python
