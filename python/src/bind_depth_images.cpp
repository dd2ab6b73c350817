// Depth images and what is made of them: sampling (depthimage/sampling.h) from any cameras,
// meshes reconstructed from the samples (reconstruct/reconstruction.h), and soft shadows of
// an area light through reconstructed occluders (study/shadows.h: the setting built once,
// any sampling rendered on it).
#include <memory>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "proxima/core/camera.h"
#include "proxima/core/limits.h"
#include "proxima/core/range_check.h"
#include "proxima/reconstruct/reconstruction.h"
#include "proxima/shadows/shadow_error.h"
#include "proxima/study/sampling.h"
#include "proxima/study/shadows.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

py::dict sampling_views_py(const SceneHandle& handle, const std::string& camera, int width, int height,
                           const std::string& views, float radius) {
  study::SamplingOptions o;
  o.camera.camera = camera;
  o.width = width;
  o.height = height;
  o.views = parse_view_shape(views, "views");
  o.radius = radius;
  o.methods = {study::SamplingMethod::Conventional};
  study::validate(o, handle.scene());
  const study::SamplingViews v = study::sampling_views(handle.scene(), o);
  py::dict out;
  out["corners"] = v.corners;
  out["centroid"] = v.centroid;
  return out;
}

// The arguments of a sampling call, checked: the method, 1..64 cameras (one for peeling,
// with 1..64 layers), each a valid camera within the image budget.
study::SamplingMethod checked_sampling(const std::vector<Camera>& cameras, const std::string& method, int layers) {
  const study::SamplingMethod m = study::parse_sampling_method(method, "method");
  if (cameras.empty() || cameras.size() > 64) fail_input("cameras: expected 1..64 cameras");
  if (m == study::SamplingMethod::Peeling) {
    if (cameras.size() != 1) fail_input("cameras: peeling samples from one camera");
    require_in_range(layers, 1, 64, "layers");
  }
  for (const Camera& c : cameras) {
    validate_camera(c, "cameras");
    check_image_budget("cameras", uint64_t(c.width), uint64_t(c.height), 16);
  }
  return m;
}

// The depth images of `cameras` by method `m` (arguments checked); call without the GIL.
std::vector<DepthImage> sample_images(const SceneHandle& handle, const std::vector<Camera>& cameras,
                                      study::SamplingMethod m, int layers, bool shade) {
  const auto lock = handle.read_lock();
  const Scene& scene = handle.scene();
  switch (m) {
    case study::SamplingMethod::Conventional: return sample_conventional(scene, cameras, shade);
    case study::SamplingMethod::Peeling: return sample_peeling(scene, cameras[0], layers, shade);
    case study::SamplingMethod::NrrPixel: return sample_nrr(scene, cameras, Redundancy::Pixel, &handle.rays(), shade);
    case study::SamplingMethod::NrrVisibility:
      return sample_nrr(scene, cameras, Redundancy::Visibility, &handle.rays(), shade);
  }
  return {};
}

py::list sample_depth_images_py(const SceneHandle& handle, const std::vector<Camera>& cameras,
                                const std::string& method, int layers, bool shade) {
  const study::SamplingMethod m = checked_sampling(cameras, method, layers);
  std::vector<DepthImage> images;
  {
    py::gil_scoped_release release;
    images = sample_images(handle, cameras, m, layers, shade);
  }
  py::list out;
  for (DepthImage& image : images) {
    py::dict d = named({{"camera", image.camera}, {"depth", image_array(std::move(image.depth))},
        {"id", id_image_array(std::move(image.triangle))}});
    if (shade) {
      d["normal"] = image_array(std::move(image.normal));
      d["color"] = image_array(std::move(image.color));
    }
    out.append(d);
  }
  return out;
}

// The cameras of the offset images H: one per camera, or per peeling layer.
std::vector<Camera> offset_cameras(const std::vector<Camera>& cameras) {
  std::vector<Camera> out;
  for (const Camera& c : cameras) out.push_back(half_pixel_offset_camera(c));
  return out;
}

py::list reconstruct_py(const SceneHandle& handle, const std::vector<Camera>& cameras, const std::string& method,
                        const std::string& reconstruction, int layers, bool merge_planar_runs) {
  const study::SamplingMethod m = checked_sampling(cameras, method, layers);
  const bool hybrid = parse_reconstruction(reconstruction, "reconstruction") == ReconstructionMethod::Hybrid;
  std::vector<DepthImage> images;
  std::vector<Mesh> meshes;
  std::vector<HybridStats> stats;
  {
    py::gil_scoped_release release;
    images = sample_images(handle, cameras, m, layers, true);
    const std::vector<DepthImage> offsets =
        hybrid ? sample_images(handle, offset_cameras(cameras), m, layers, true) : std::vector<DepthImage>{};
    stats.resize(images.size());
    for (size_t i = 0; i < images.size(); ++i)
      meshes.push_back(hybrid ? reconstruct_hybrid(images[i], offsets[i], &stats[i], merge_planar_runs)
                              : reconstruct_conventional(images[i]));
  }
  py::list out;
  for (size_t i = 0; i < images.size(); ++i) {
    py::dict d = mesh_dict(std::move(meshes[i]));
    d["camera"] = images[i].camera;
    d["samples"] = sample_count(images[i]);
    if (hybrid) {
      d["corners_from_h"] = stats[i].corners_from_h;
      d["corners_fitted"] = stats[i].corners_fitted;
    }
    out.append(d);
  }
  return out;
}

// The soft-shadow setting of one output camera (light, samples, receivers, light cameras,
// ground truths), built once; render() runs one sampling on it.
class SoftShadows {
 public:
  SoftShadows(std::shared_ptr<SceneHandle> handle, const Camera& camera, const study::ShadowsOptions& o)
      : handle_(std::move(handle)), options_(o) {
    study::validate(o);
    validate_camera(camera, "camera");
    const uint64_t words = (uint64_t(o.light_samples) * uint64_t(o.light_samples) + 63) / 64;
    check_image_budget("camera", uint64_t(camera.width), uint64_t(camera.height), 16 + 16 * words);
    py::gil_scoped_release release;
    const auto lock = handle_->read_lock();
    setting_ = study::shadow_setting(handle_->scene(), handle_->rays(), camera, o);
  }

  py::dict render(const std::string& sampling_name, int ref_res, const std::string& redundancy,
                  const std::string& reconstruction) const {
    study::ShadowsOptions o = options_;
    o.ref_res = ref_res;
    o.redundancy = parse_redundancy(redundancy, "redundancy");
    o.reconstruction = parse_reconstruction(reconstruction, "reconstruction");
    study::validate(o);
    const ShadowSampling sampling = parse_shadow_sampling(sampling_name, "sampling");
    study::ShadowSamplingRun run;
    ShadowError truth_error, rays_error;
    {
      py::gil_scoped_release release;
      const auto lock = handle_->read_lock();
      run = study::run_shadow_sampling(handle_->scene(), handle_->rays(), setting_, o, sampling);
      truth_error = compare_visibility(run.visibility, setting_.truth, setting_.receivers);
      if (!o.no_rays) rays_error = compare_visibility(run.visibility, setting_.exact, setting_.receivers);
    }
    py::dict out = visibility_dict(run.visibility);
    out["error"] = image_array(std::move(truth_error.image));
    py::dict errors;
    add_errors(errors, "_", truth_error);
    if (!o.no_rays) add_errors(errors, "_rays_", rays_error);
    out["errors"] = errors;
    py::dict stats = named({{"time_reference_ms", run.occluders.reference_ms},
        {"time_reconstruct_ms", run.occluders.reconstruct_ms}, {"time_shadow_ms", run.shadow_ms},
        {"occluder_triangles", run.occluders.scene.triangles.size()},
        {"reference_samples", run.occluders.samples}});
    out["stats"] = stats;
    Mesh occluders;
    occluders.positions = std::move(run.occluders.scene.positions);
    occluders.normals = std::move(run.occluders.scene.normals);
    occluders.triangles = std::move(run.occluders.scene.triangles);
    out["occluders"] = mesh_dict(std::move(occluders));
    return out;
  }

  py::dict truth() const { return visibility_dict(setting_.truth); }
  py::object exact() const { return options_.no_rays ? py::object(py::none()) : visibility_dict(setting_.exact); }

  std::vector<Camera> light_cameras(const std::string& sampling, int ref_res) const {
    require_in_range(ref_res, 8, kMaxImageSide, "ref_res");
    return occluder_cameras(setting_.light, setting_.cams, parse_shadow_sampling(sampling, "sampling"), ref_res);
  }

  py::dict receivers() const {
    const Receivers& r = setting_.receivers;
    return named({{"camera", r.camera}, {"position", image_copy_array(r.position)},
        {"normal", image_copy_array(r.normal)}, {"mask", image_array<bool>(ImageU8(r.mask))},
        {"count", r.count}});
  }

  py::array light_sample_positions() const {
    std::vector<vec3> samples = setting_.samples.points;
    const auto n = py::ssize_t(samples.size());
    return buffer_array<float>(std::move(samples), {n, 3});
  }

  py::array light_corners_array() const {
    std::vector<vec3> corners = light_corners(setting_.light);
    return buffer_array<float>(std::move(corners), {4, 3});
  }

 private:
  // lit (H×W float32, the fraction of light samples lit; 0 off the receivers) and shadow
  // (H×W×3 float32, the study's shadow image).
  py::dict visibility_dict(const LightVisibility& v) const {
    const Receivers& r = setting_.receivers;
    ImageF lit(v.width, v.height, 1, 0.0f);
    const float n = float(v.samples);
    for (int y = 0; y < v.height; ++y)
      for (int x = 0; x < v.width; ++x)
        if (r.mask.at(x, y)) lit.at(x, y) = float(v.lit_count(x, y)) / n;
    py::dict out;
    out["lit"] = image_array(std::move(lit));
    out["shadow"] = image_array(shadow_image(v, r));
    return out;
  }

  static void add_errors(py::dict& errors, const std::string& suffix, const ShadowError& e) {
    errors[py::str("intensity_error" + suffix + "mean")] = e.intensity_mean;
    errors[py::str("intensity_error" + suffix + "max")] = e.intensity_max;
    errors[py::str("visibility_error" + suffix + "mean")] = e.visibility_mean;
    errors[py::str("visibility_error" + suffix + "max")] = e.visibility_max;
  }

  std::shared_ptr<SceneHandle> handle_;
  study::ShadowsOptions options_;
  study::ShadowSetting setting_;
};

std::unique_ptr<SoftShadows> make_soft_shadows(std::shared_ptr<SceneHandle> scene, const Camera& camera,
                                               float light_size, int light_samples, int shadow_res, bool rays) {
  study::ShadowsOptions o;
  o.light_size = light_size;
  o.light_samples = light_samples;
  o.shadow_res = shadow_res;
  o.no_rays = !rays;
  return std::make_unique<SoftShadows>(std::move(scene), camera, o);
}

void bind_sampling(py::module_& m) {
  m.def("sampling_views", &sampling_views_py, py::arg("scene"), py::kw_only(), py::arg("camera") = "",
        py::arg("width") = 1024, py::arg("height") = 1024, py::arg("views") = "triangle", py::arg("radius") = 0.0f,
        "The view set of `proxima sample` (docs/depthimage.md): centred on the scene camera `camera` (name or "
        "index; '' = the first) at width × height, views 'segment', 'triangle' or 'rectangle', corners `radius` "
        "m from the centre (0 = 8 % of the distance to the scene's centre). Returns a dict: corners (list of "
        "Camera: conventional and NRR sample from these), centroid (Camera: peeling samples from it).");
  m.def("sample_depth_images", &sample_depth_images_py, py::arg("scene"), py::arg("cameras"),
        py::arg("method") = "nrr-pixel", py::kw_only(), py::arg("layers") = 0, py::arg("shade") = true,
        "Depth images of the scene (rest pose, back faces culled) by `method`: 'conventional' (one per camera), "
        "'nrr-pixel' / 'nrr-visibility' (non-redundant rendering over the cameras in order: image i keeps "
        "only fragments not redundant with images 0..i−1), 'peeling' (`layers` layers from the one camera). "
        "GIL released. Returns a list of dicts, one per image: camera, depth (H×W float32, −z_camera in m, "
        "+inf where empty), id (H×W int32 triangle id, −1 where empty), and with shade normal (H×W×3 float32, "
        "unit world normal facing the camera) and color (H×W×3 float32, linear direct light without shadows).");
  m.def("reconstruct", &reconstruct_py, py::arg("scene"), py::arg("cameras"), py::arg("method") = "nrr-pixel",
        py::kw_only(), py::arg("reconstruction") = "hybrid", py::arg("layers") = 4,
        py::arg("merge_planar_runs") = false,
        "Triangle meshes reconstructed from depth images (thesis ch. 3, docs/shadows.md): the images of "
        "sample_depth_images(scene, cameras, method, layers=layers) each become a mesh. reconstruction "
        "'hybrid' (Algorithm 4: one quad per sample, corners from the half-pixel offset image H — sampled "
        "with the same method from the offset cameras — or from the sample's tangent plane) or "
        "'conventional' (two triangles per 2×2 pixel quad of continuous samples). GIL released. Returns a "
        "list of dicts, one per image: positions (V×3 float32, world m), normals (V×3 float32 unit, 0×3 "
        "when the method makes none), triangles "
        "(T×3 uint32, counter-clockwise seen from the image's camera), camera, samples (pixels holding a "
        "sample) and with 'hybrid' corners_from_h, corners_fitted. merge_planar_runs (hybrid): consecutive "
        "quads of a row that share their corners and lie on one plane become one quad (the same surface, "
        "fewer triangles; the soft-shadow occluders are built so).");
}

void bind_soft_shadows(py::module_& m) {
  const study::ShadowsOptions d;
  py::class_<SoftShadows>(
      m, "SoftShadows",
      "Soft shadows of a rectangular area light through reconstructed occluders (thesis ch. 3, Algorithm 5, "
      "docs/shadows.md), for the receivers seen by `camera` (its visible points, back faces culled). Built once "
      "at construction (GIL released): the light (its diagonal light_size × the scene's bounding-box diagonal, "
      "centred on the scene's first point light), its light_samples × light_samples samples, the light "
      "cameras, the ground truth (shadow maps of the original geometry, shadow_res² texels) and, with rays, "
      "exact visibility by Embree shadow rays. render() runs one sampling on it; `proxima shadows` with "
      "--out-res = the camera's size computes the same numbers.")
      .def(py::init(&make_soft_shadows), py::arg("scene"), py::arg("camera"), py::kw_only(),
           py::arg("light_size") = d.light_size, py::arg("light_samples") = d.light_samples,
           py::arg("shadow_res") = d.shadow_res, py::arg("rays") = !d.no_rays)
      .def("render", &SoftShadows::render, py::arg("sampling") = "nrr", py::kw_only(),
           py::arg("ref_res") = d.ref_res, py::arg("redundancy") = "pixel", py::arg("reconstruction") = "hybrid",
           "Steps 1–3 for `sampling` ('nrr', 'conventional', 'peeling' or 'geometry'): depth images of ref_res² "
           "pixels from the light (NRR with `redundancy` 'pixel' or 'visibility'), reconstructed "
           "('hybrid' or 'conventional') into occluders, the receivers' visibility of every light sample "
           "through shadow maps of them. GIL released. Returns a dict: lit (H×W float32, fraction of light "
           "samples lit, 0 off the receivers), shadow (H×W×3 float32, the study's shadow image), error (H×W×3 "
           "float32: green too bright, red too dark), errors (dict: intensity_error_mean/_max, "
           "visibility_error_mean/_max on 0..255 against the ground truth; with rays the same with _rays_ "
           "against Embree), stats (time_reference_ms, time_reconstruct_ms, time_shadow_ms, "
           "occluder_triangles, reference_samples), occluders (positions V×3 float32, normals V×3 float32, triangles "
           "T×3 uint32).")
      .def("truth", &SoftShadows::truth,
           "The ground truth (shadow maps of the original geometry): dict with lit and shadow as render().")
      .def("exact", &SoftShadows::exact, "Embree's exact visibility as truth(); None when built with rays=False.")
      .def("light_cameras", &SoftShadows::light_cameras, py::arg("sampling") = "nrr", py::kw_only(),
           py::arg("ref_res") = d.ref_res,
           "The cameras step 1 samples from for `sampling` at ref_res² pixels: the light's four corners (nrr, "
           "conventional; in the order NRR uses) or its centre (peeling); none for geometry.")
      .def_property_readonly("receivers", &SoftShadows::receivers,
                             "The receivers: dict with camera, position (H×W×3 float32, world m), normal (H×W×3 "
                             "float32, unit), mask (H×W bool, a surface is seen), count.")
      .def_property_readonly("light_samples", &SoftShadows::light_sample_positions,
                             "The light's sample points, n²×3 float32 (world m), row-major over its cells.")
      .def_property_readonly("light_corners", &SoftShadows::light_corners_array,
                             "The light's four corners, 4×3 float32 (world m), in order around it.");
}

}  // namespace

void bind_depth_images(py::module_& m) {
  bind_sampling(m);
  bind_soft_shadows(m);
}

}  // namespace proxima::python
