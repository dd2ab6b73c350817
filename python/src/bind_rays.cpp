// RayScene: batched Embree ray casts from numpy arrays (trace/ray_batch.h).
#include "arrays.h"
#include "bindings.h"
#include "proxima/trace/ray_batch.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

// The rays of a scene: holds the scene (and so its BVH) alive, and the per-triangle hit
// records every cast reads (geometry is read-only from Python, so they stay valid).
struct PyRayScene {
  std::shared_ptr<SceneHandle> scene;
  std::shared_ptr<const LargeBuffer<TriangleHitRecord>> records;
};

std::span<const vec3> as_vec3s(const py::array_t<float, py::array::c_style>& a) {
  return {reinterpret_cast<const vec3*>(a.data()), size_t(a.shape(0))};
}

py::dict cast(const PyRayScene& self, py::handle origins_obj, py::handle directions_obj, float tmin,
              float tmax) {
  const auto origins = checked_rows<float>(origins_obj, "origins", 3);
  const auto directions = checked_rows<float>(directions_obj, "directions", 3);
  RayBatchHits hits;
  {
    py::gil_scoped_release release;
    hits = cast_ray_batch(*self.records, self.scene->rays(), as_vec3s(origins), as_vec3s(directions), tmin,
                          tmax);
  }
  const auto n = py::ssize_t(hits.t.size());
  py::dict out;
  out["t"] = buffer_array<float>(std::move(hits.t), {n});
  out["triangle"] = buffer_array<int32_t>(std::move(hits.triangle), {n});
  out["object"] = buffer_array<int32_t>(std::move(hits.object), {n});
  out["normal"] = buffer_array<float>(std::move(hits.normal), {n, 3});
  out["uv"] = buffer_array<float>(std::move(hits.uv), {n, 2});
  return out;
}

}  // namespace

void bind_rays(py::module_& m) {
  static_assert(sizeof(vec3) == 3 * sizeof(float) && sizeof(vec2) == 2 * sizeof(float));
  py::class_<PyRayScene>(m, "RayScene",
                         "Embree ray queries on a scene's triangles (its rest pose). Shares the scene's BVH, "
                         "built on first use.")
      .def(py::init([](std::shared_ptr<SceneHandle> scene) {
             if (!scene) fail_input("RayScene: scene is None");
             std::shared_ptr<const LargeBuffer<TriangleHitRecord>> records;
             {
               py::gil_scoped_release release;
               scene->rays();  // the build happens here, not in the first cast
               records = std::make_shared<const LargeBuffer<TriangleHitRecord>>(
                   triangle_hit_records(scene->scene()));
             }
             return PyRayScene{std::move(scene), std::move(records)};
           }),
           py::arg("scene"))
      .def_property_readonly("scene", [](const PyRayScene& r) { return r.scene; })
      .def("cast", &cast, py::arg("origins"), py::arg("directions"), py::arg("tmin") = 0.0f,
           py::arg("tmax") = std::numeric_limits<float>::infinity(),
           "Closest hit of each ray origins[i] + t·directions[i], t in [tmin, tmax]. origins, directions: "
           "N×3 float32, world space (m); directions need not be unit (t is in units of their length) but "
           "not zero. Returns a dict of arrays, index i = ray i: t (N float32, +inf on a miss), triangle (N "
           "int32 triangle id, −1 on a miss), object (N int32 object id, −1), normal (N×3 float32 unit "
           "geometric normal, right-hand rule over the triangle's vertex order, 0 on a miss), uv (N×2 "
           "float32 barycentrics: p = (1−u−v)·p0 + u·p1 + v·p2). Parallel, GIL released; results do not "
           "depend on the thread count.");
}

}  // namespace proxima::python
