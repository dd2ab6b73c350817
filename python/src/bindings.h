// The parts of the extension module _proxima: one bind_* function per group of the API,
// each defined in its own bind_*.cpp and called once from module.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace proxima::python {

namespace py = pybind11;

void bind_scene(py::module_& m);       // load_scene, Scene, Camera, materials, paths
void bind_render(py::module_& m);      // render_reference, rasterize
void bind_rays(py::module_& m);        // RayScene: batched ray casts from numpy
void bind_eval(py::module_& m);        // image_error, read_exr, write_exr
void bind_techniques(py::module_& m);  // the reflection techniques on cameras
void bind_depth_images(py::module_& m);  // sampling, reconstruction, soft shadows
void bind_visibility(py::module_& m);  // VisibilityMaps: exact visibility maps
void bind_gibr(py::module_& m);        // GibrModel: image-based rendering from photographs
void bind_studies(py::module_& m);     // proxima.study: the studies of the command line

}  // namespace proxima::python
