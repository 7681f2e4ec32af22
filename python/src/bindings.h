// Shared pieces of the Python bindings: numpy arrays from OpenCV images, Python objects from
// JSON text, and the functions that add each group of bindings to the module.
#pragma once

#include <string>

#include <opencv2/core.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace hoilcd::python {

namespace py = pybind11;

// A copy of a single-channel image as an H x W numpy array of T (T must match the image's depth).
template <typename T>
py::array_t<T> ImageToArray(const cv::Mat& image) {
  py::array_t<T> array({image.rows, image.cols});
  T* out = array.mutable_data();
  for (int row = 0; row < image.rows; ++row) {
    const T* in = image.ptr<T>(row);
    std::copy(in, in + image.cols, out + static_cast<size_t>(row) * image.cols);
  }
  return array;
}

// json.loads(text): dicts, lists, numbers and strings.
py::object JsonToPython(const std::string& text);
// json.dumps(value) as a string.
std::string PythonToJson(const py::handle& value);

void BindDataset(py::module_& m);
void BindRun(py::module_& m);

}  // namespace hoilcd::python
