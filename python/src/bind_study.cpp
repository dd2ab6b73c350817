// proxima.study: each study of the command line as a function returning its metrics,
// tables and images.
#include "arrays.h"
#include "bindings.h"

namespace proxima::python {

void bind_studies(py::module_& /*m*/) {}

}  // namespace proxima::python
