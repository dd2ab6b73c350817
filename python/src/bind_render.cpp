// render_reference (the Embree ground truth, trace/reference_renderer.h) and rasterize
// (raster/rasterizer.h) on a scene and a camera, images out as numpy arrays.
#include <optional>

#include "arrays.h"
#include "bindings.h"
#include "proxima/core/camera.h"
#include "proxima/core/limits.h"
#include "proxima/core/parallel.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/study/reference.h"
#include "proxima/trace/reference_renderer.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

struct Rendered {
  ImageF color;
  ItemBuffer item;
};

// The item buffer and the reference image, as `proxima render` computes them.
Rendered render(const SceneHandle& handle, const Camera& camera, const ReferenceOptions& options,
                std::optional<float> time) {
  const auto lock = handle.read_lock();
  const Scene& rest = handle.scene();
  if (time && has_animation(rest)) {
    const Scene posed = pose_scene(rest, *time);
    const RayScene rays(posed);
    return {render_reference(posed, rays, camera, options), trace_item_buffer(posed, rays, camera)};
  }
  const RayScene& rays = handle.rays();
  return {render_reference(rest, rays, camera, options), trace_item_buffer(rest, rays, camera)};
}

py::dict render_reference_py(const SceneHandle& handle, const Camera& camera, int spp, int light_samples,
                             int glossy_rays, int bounces, uint64_t seed, std::optional<float> time) {
  study::ReferenceStudyOptions o;
  o.supersample = spp;
  o.light_samples = light_samples;
  o.glossy_rays = glossy_rays;
  o.bounces = bounces;
  o.seed = seed;
  study::validate(o);
  validate_camera(camera, "camera");
  // color, normal and position (3 channels each), depth, id, barycentrics.
  check_image_budget("camera", uint64_t(camera.width), uint64_t(camera.height), 12);
  if (time && !(*time >= 0.0f && std::isfinite(*time))) fail_input("time: must be finite and ≥ 0");
  // Animated scenes pose at 0 s by default, as `proxima render` without --time and --path.
  if (!time && has_animation(handle.scene())) time = 0.0f;
  Rendered r;
  {
    py::gil_scoped_release release;
    r = render(handle, camera, study::reference_options(o), time);
  }
  py::dict out;
  out["color"] = image_array(std::move(r.color));
  out["depth"] = image_array(std::move(r.item.depth));
  out["normal"] = image_array(std::move(r.item.normal));
  out["position"] = image_array(std::move(r.item.position));
  out["id"] = id_image_array(std::move(r.item.triangle));
  return out;
}

py::dict rasterize_py(const SceneHandle& handle, const Camera& camera, const std::string& cull) {
  RasterOptions options;
  options.outputs = kRasterDepth | kRasterTriangle | kRasterObject;
  if (cull == "back") options.cull = CullMode::Back;
  else if (cull != "none") fail_input("cull: expected 'none' or 'back', got '" + cull + "'");
  validate_camera(camera, "camera");
  check_image_budget("camera", uint64_t(camera.width), uint64_t(camera.height), 3);
  RasterImages images;
  {
    py::gil_scoped_release release;
    images = rasterize(handle.scene(), camera, options);
  }
  py::dict out;
  out["depth"] = image_array(std::move(images.depth));
  out["id"] = id_image_array(std::move(images.triangle));
  out["object"] = id_image_array(std::move(images.object));
  return out;
}

// The process-wide worker-thread limit of set_threads.
std::unique_ptr<ThreadLimit> g_thread_limit;

void set_threads(int threads) {
  if (threads < 0) fail_input("threads: must be ≥ 0 (0 = all cores)");
  g_thread_limit.reset();
  if (threads > 0) g_thread_limit = std::make_unique<ThreadLimit>(threads);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("set_threads", &set_threads, py::arg("threads"),
        "Limits the worker threads of every parallel call of the process (0 = all cores), like the "
        "command line's --threads. Results do not depend on it. Each Python thread that calls proxima "
        "runs its own parallel loops within this limit.");
  m.def("threads", &active_threads, "Worker threads the parallel calls may use now.");
  m.def("hardware_threads", &hardware_threads, "Hardware threads of this machine.");
  // The limit ends before the interpreter unloads the module (TBB's global control).
  m.add_object("_thread_limit_cleanup", py::capsule([] { g_thread_limit.reset(); }));
  m.def("render_reference", &render_reference_py, py::arg("scene"), py::arg("camera"), py::kw_only(),
        py::arg("spp") = 1, py::arg("light_samples") = 4, py::arg("glossy_rays") = 16, py::arg("bounces") = 2,
        py::arg("seed") = 1, py::arg("time") = py::none(),
        "The reference image (Embree ray tracing, docs/shading.md) and its primary-visibility buffers, "
        "bit for bit what `proxima render` computes with the same settings. spp: k, k×k stratified samples "
        "per pixel (1..64); light_samples: n, n×n samples per area light (1..64); glossy_rays: rays per "
        "glossy lobe (1..4096); bounces: reflection depth (0..16); seed: sample streams; time: pose time "
        "in seconds of animated scenes (default 0). Returns a dict of H×W(×C) arrays, row 0 on top: color "
        "(H×W×3 float32, linear RGB), depth (H×W float32, view depth −z_camera in m, +inf on a miss), "
        "normal (H×W×3 float32, unit world shading normal facing the camera, 0 on a miss), position "
        "(H×W×3 float32, world position in m, 0 on a miss), id (H×W int32 triangle id, −1 on a miss). "
        "Parallel, GIL released; the same bits for any thread count.");
  m.def("rasterize", &rasterize_py, py::arg("scene"), py::arg("camera"), py::kw_only(), py::arg("cull") = "none",
        "Rasterizes the scene (raster/rasterizer.h: exact coverage at pixel centers, top-left rule). "
        "cull: 'none' or 'back'. Returns a dict of H×W arrays: depth (float32, view depth −z_camera in m, "
        "+inf where empty), id (int32 triangle id, −1 where empty), object (int32 object id, −1 where "
        "empty). GIL released.");
}

}  // namespace proxima::python
