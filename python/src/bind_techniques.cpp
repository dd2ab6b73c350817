// The techniques on arrays and cameras (env-map and cluster reflections, temporal reuse,
// depth-image sampling, reconstruction and soft shadows, visibility maps, GIBR).
#include "arrays.h"
#include "bindings.h"

namespace proxima::python {

void bind_techniques(py::module_& /*m*/) {}

}  // namespace proxima::python
