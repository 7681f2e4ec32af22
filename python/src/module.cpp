// The hoilcd Python module (_hoilcd, re-exported by the hoilcd package): the error class and
// the module-level functions; the bindings live in dataset_bindings.cpp and run_bindings.cpp.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/sim/assets/data_dir.h"

namespace py = pybind11;

PYBIND11_MODULE(_hoilcd, m) {
  m.doc() = "hoilcd: synthetic thermal scene simulator and loop-closure benchmark";
  m.attr("__version__") = HOILCD_VERSION;
  hoilcd::KeepOpenCvOnCallingThread();  // render and bench run on their `threads`, as in the CLI
  // hoilcd's InputError (bad scene, dataset, scores or argument) keeps its message, which names
  // the file, JSON pointer or line and what was expected.
  py::register_exception<hoilcd::InputError>(m, "InputError", PyExc_ValueError);
  m.def("data_dir", &hoilcd::DataDir,
        "The folder holding hoilcd's scenes/ and assets/ ($HOILCD_DATA_DIR, else share/hoilcd of the "
        "installation or build tree).");
  hoilcd::python::BindDataset(m);
  hoilcd::python::BindRun(m);
}
