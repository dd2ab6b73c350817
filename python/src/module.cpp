// The extension module proxima._proxima; the package proxima (python/proxima/__init__.py)
// re-exports it. docs/python.md describes the API.
#include "arrays.h"
#include "bindings.h"

PYBIND11_MODULE(_proxima, m) {
  using namespace proxima::python;
  m.doc() = "proxima: approximate representations of 3D scenes measured against an Embree reference";
  register_exceptions(m);
  bind_scene(m);
  bind_render(m);
  bind_rays(m);
  bind_eval(m);
  bind_techniques(m);
  bind_depth_images(m);
  bind_visibility(m);
  bind_gibr(m);
  bind_studies(m);
}
