// The pieces of the lpir_gseg._core module, one Bind* per source file; module.cpp joins them.
#pragma once
#include <pybind11/pybind11.h>

#include <string>

namespace lpir::python {

namespace py = pybind11;

// The folder of the sensor profiles that names resolve in: lpir_gseg/sensors of the installed
// package (lpir_gseg/__init__.py sets it at import).
std::string SensorsDir();
void SetSensorsDir(const std::string& dir);

void BindSegmenter(py::module_& m);  // segmenter.cpp: Segmenter
void BindFunctions(py::module_& m);  // functions.cpp: files, scores, simulator, sensors, devices
void BindDrive(py::module_& m);      // drive.cpp: recorded drives

}  // namespace lpir::python
