// lpir_gseg._core: the library for Python. IoError (host/io/io_error.h, whose message names the
// file) and filesystem errors become OSError, or the subclass Python gives their errno
// (FileNotFoundError for a missing file, IsADirectoryError, PermissionError); std::invalid_argument
// and std::length_error become ValueError (pybind11's own mapping), other library errors
// RuntimeError.
#include <pybind11/pybind11.h>

#include <cerrno>
#include <filesystem>
#include <mutex>
#include <string>

#include "bindings.h"
#include "host/io/io_error.h"
#include "reference_cpu/frame.h"

namespace lpir::python {
namespace {

// The OSError subclass Python raises for `error_number` (an errno), OSError itself for 0 and
// the rest.
PyObject* OsErrorFor(int error_number) {
  switch (error_number) {
    case ENOENT:
      return PyExc_FileNotFoundError;
    case EISDIR:
      return PyExc_IsADirectoryError;
    case ENOTDIR:
      return PyExc_NotADirectoryError;
    case EACCES:
    case EPERM:
      return PyExc_PermissionError;
    default:
      return PyExc_OSError;
  }
}

std::mutex sensors_dir_mutex;
std::string sensors_dir;  // guarded by sensors_dir_mutex

}  // namespace

std::string SensorsDir() {
  std::lock_guard<std::mutex> lock(sensors_dir_mutex);
  return sensors_dir;
}

void SetSensorsDir(const std::string& dir) {
  std::lock_guard<std::mutex> lock(sensors_dir_mutex);
  sensors_dir = dir;
}

}  // namespace lpir::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace lpir::python;
  m.doc() = "The lpir-gseg library (C++): use it through the lpir_gseg package.";
  // Every docstring opens with its Python signature ("name(...)\n--\n\n": inspect.signature
  // reads it) instead of pybind11's, which would show the C++ parameter types.
  py::options options;
  options.disable_function_signatures();
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const lpir::IoError& e) {
      PyErr_SetString(OsErrorFor(e.error_number()), e.what());
    } catch (const std::filesystem::filesystem_error& e) {
      PyErr_SetString(OsErrorFor(e.code().value()), e.what());
    }
  });
  m.def("_set_sensors_dir", &SetSensorsDir, py::arg("path"),
        "_set_sensors_dir(path)\n--\n\nWhere profile names resolve (the package sets its own "
        "sensors/ folder at import).");
  m.attr("WHY_NON_GROUND") = int(lpir::kWhyNonGround);
  m.attr("WHY_GROUND") = int(lpir::kWhyGround);
  m.attr("WHY_INVALID") = int(lpir::kWhyInvalid);
  m.attr("WHY_NOISE") = int(lpir::kWhyNoise);
  BindSegmenter(m);
  BindFunctions(m);
  BindDrive(m);
}
