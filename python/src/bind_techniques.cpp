// The techniques on arrays and cameras: env-map reflections (reflect/envmap_reflection.h)
// with their maps built once per object and any number of cameras rendered from them, and
// temporal reuse of reflections (reflect/temporal_reuse.h) as an object stepping frames, and
// cluster reflections (reflect/cluster_reflection.h) per camera.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "proxima/core/camera.h"
#include "proxima/core/limits.h"
#include "proxima/core/range_check.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/cluster_reflection.h"
#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/envmap_lookup.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/envmap_set.h"
#include "proxima/study/cluster_reflect.h"
#include "proxima/study/envmap_reflect.h"
#include "proxima/study/temporal_reflect.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

// The maps of every env-map method, one set per group of reflectors (reflect/envmap_set.h),
// built from the scene's rest pose and materials at construction, and the lookup settings
// of the study's flags.
class EnvmapReflections {
 public:
  EnvmapReflections(std::shared_ptr<SceneHandle> handle, const study::EnvmapReflectOptions& o)
      : handle_(std::move(handle)) {
    study::EnvmapReflectOptions all = o;
    all.compare = true;  // every map: the budget check covers the layers too
    study::validate(all);
    const Scene& scene = handle_->scene();
    reflectors_ = reflective_objects(scene);
    if (reflectors_.empty()) fail_input("scene: '" + scene.name + "' has no reflective object");
    EnvmapSetOptions so;
    so.grouping = {o.group_parallax, o.max_maps};
    so.map.resolution = o.cube_size;
    so.map.area_light_samples = o.light_samples;
    so.map.seed = o.seed;
    so.average_step_rad = glm::radians(o.angle_step_deg);
    so.layers = o.layers;
    py::gil_scoped_release release;
    const auto lock = handle_->read_lock();
    set_ = build_envmap_set(scene, handle_->rays(), reflectors_, so);
    inputs_ = with_envmap_set(study::envmap_inputs(scene, o), set_);
  }

  py::dict render(const Camera& camera, const std::string& method) const {
    EnvmapInputs in = inputs_;
    in.method = parse_envmap_method(method, "method");
    validate_camera(camera, "camera");
    check_image_budget("camera", uint64_t(camera.width), uint64_t(camera.height), 8);
    ReflectorPixels pixels;
    EnvmapFrame frame;
    {
      py::gil_scoped_release release;
      const auto lock = handle_->read_lock();
      pixels = rasterize_reflector_pixels(handle_->scene(), camera, reflectors_);
      frame = shade_reflector_pixels(handle_->scene(), handle_->rays(), camera, pixels, in);
    }
    py::dict stats = named({{"pixels", frame.stats.pixels}, {"lookups", frame.stats.lookups},
        {"map_samples", frame.stats.map_samples}, {"edge_lookups", frame.stats.edge_lookups},
        {"fallback_lookups", frame.stats.fallback_lookups}});
    return named({{"color", image_array(std::move(frame.color))},
        {"object", id_image_array(std::move(frame.object))},
        {"triangle", id_image_array(std::move(pixels.triangle))}, {"stats", stats}});
  }

  const std::vector<uint32_t>& reflectors() const { return reflectors_; }
  py::list groups() const {
    py::list out;
    for (size_t g = 0; g < set_.groups.size(); ++g) {
      const EnvmapGroup& group = set_.groups[g];
      out.append(named({{"reflectors", py::cast(group.reflectors)},
                        {"center", py::make_tuple(group.center.x, group.center.y, group.center.z)},
                        {"radius_m", group.radius}, {"parallax", group.parallax},
                        {"average_distance_m", set_.maps[g].average_distance}}));
    }
    return out;
  }
  float search_length_m() const { return inputs_.rectify.D; }
  size_t layer_count() const { return set_.maps.empty() ? 0 : set_.maps[0].layers.size(); }

 private:
  std::shared_ptr<SceneHandle> handle_;
  std::vector<uint32_t> reflectors_;
  EnvmapSet set_;
  EnvmapInputs inputs_;
};

std::unique_ptr<EnvmapReflections> make_envmap(std::shared_ptr<SceneHandle> scene, int cube_size, int light_samples,
                                               int glossy_rays, uint64_t seed, float d_e, float distance,
                                               float angle_step_deg, const std::string& edge, int layers,
                                               int march_steps, int max_maps, float group_parallax) {
  study::EnvmapReflectOptions o;
  o.cube_size = cube_size;
  o.light_samples = light_samples;
  o.glossy_rays = glossy_rays;
  o.seed = seed;
  o.d_e = d_e;
  o.distance = distance;
  o.angle_step_deg = angle_step_deg;
  o.edge = edge;
  o.layers = layers;
  o.march_steps = march_steps;
  o.max_maps = max_maps;
  o.group_parallax = group_parallax;
  return std::make_unique<EnvmapReflections>(std::move(scene), o);
}

void bind_envmap(py::module_& m) {
  const study::EnvmapReflectOptions d;
  py::class_<EnvmapReflections>(
      m, "EnvmapReflections",
      "Reflections through environment maps with distance (Wang et al. 2012, docs/envmap.md): the distance "
      "cube map (and its average distance) and the layered maps per group of the scene's reflective objects "
      "(around the group's center, its own reflectors left out), built once from the scene's rest pose and its materials at construction; render() shades the "
      "reflector pixels of any camera with one method. The options are `proxima reflect`'s flags: cube_size "
      "(face side, texels), light_samples (n×n per area light), glossy_rays (lookups per glossy lobe), seed, "
      "d_e (rectification tolerance, m), distance (search length D, m; 0 = the scene's diagonal), "
      "angle_step_deg (step of the average distance), edge ('black' or 'fallback'), layers, march_steps, max_maps (groups at "
      "most), group_parallax (reflectors share a map while its mean parallax is at most this).")
      .def(py::init(&make_envmap), py::arg("scene"), py::kw_only(), py::arg("cube_size") = d.cube_size,
           py::arg("light_samples") = d.light_samples, py::arg("glossy_rays") = d.glossy_rays,
           py::arg("seed") = d.seed, py::arg("d_e") = d.d_e, py::arg("distance") = d.distance,
           py::arg("angle_step_deg") = d.angle_step_deg, py::arg("edge") = d.edge, py::arg("layers") = d.layers,
           py::arg("march_steps") = d.march_steps, py::arg("max_maps") = d.max_maps,
           py::arg("group_parallax") = d.group_parallax)
      .def("render", &EnvmapReflections::render, py::arg("camera"), py::arg("method") = "rectified",
           "Shades the reflector pixels seen by `camera` with `method` ('envmap', 'rectified', 'average' or "
           "'layered'); GIL released. Returns a dict: color (H×W×3 float32 linear RGB, the reflector pixels' "
           "radiance, 0 elsewhere), triangle (H×W int32, the rasterized reflector triangle, −1 on other "
           "pixels), object (H×W int32, the object the pixel's first successful lookup found, −1 elsewhere "
           "and where every lookup missed), stats (dict: pixels, lookups, map_samples, edge_lookups, "
           "fallback_lookups). The method's frame in `proxima reflect` is the reference outside the "
           "reflector pixels and this color on them.")
      .def_property_readonly("reflectors", &EnvmapReflections::reflectors,
                             "Object ids of the reflective objects (specular > 0), which the maps exclude.")
      .def_property_readonly("groups", &EnvmapReflections::groups,
                             "The reflectors' groups, one set of maps each: a list of dicts with reflectors "
                             "(object ids), center (the maps' projection center, m), radius_m, parallax and "
                             "average_distance_m (the 'average' method's d̄ of the group's map).")
      .def_property_readonly("search_length_m", &EnvmapReflections::search_length_m, "The search length D (m).")
      .def_property_readonly("layer_count", &EnvmapReflections::layer_count, "Layers of the layered maps.");
}

// Temporal reuse along any sequence of cameras: the state (key frame, offsets, buffers)
// lives in the object, each step() renders one frame. The scene's rest pose is used.
class TemporalReflections {
 public:
  TemporalReflections(std::shared_ptr<SceneHandle> handle, const study::TemporalReflectOptions& o)
      : handle_(std::move(handle)), reflection_(study::reflection_options(o)), temporal_(study::temporal_options(o)) {
    study::validate(o);
    if (reflective_objects(handle_->scene()).empty())
      fail_input("scene: '" + handle_->scene().name + "' has no reflective object");
  }

  py::dict step(const Camera& camera) {
    validate_camera(camera, "camera");
    check_image_budget("camera", uint64_t(camera.width), uint64_t(camera.height), 16);
    ImageF color;
    ImageU8 reuse(camera.width, camera.height, 1);
    ImageU8 reflective(camera.width, camera.height, 1);
    TemporalFrameStats st;
    {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> stepping(mutex_);  // one frame at a time per state
      const auto lock = handle_->read_lock();
      const Scene& scene = handle_->scene();
      const ReflectionFrame frame = prepare_reflection_frame(scene, camera, reflection_);
      temporal_reflections_into(scene, handle_->rays(), frame, state_, temporal_, reflected_, &st, &flags_);
      color = compose_reflections(frame, reflected_);
      // supersample 1: a sample's G-buffer pixel is the output pixel
      for (size_t i = 0; i < frame.sample_count(); ++i) {
        reuse.data()[frame.pixel[i]] = flags_[i];
        reflective.data()[frame.pixel[i]] = 1;
      }
      ++frames_;
    }
    py::dict stats = named({{"key", st.key}, {"reflective", st.reflective}, {"recomputed", st.recomputed},
        {"rays", st.rays}, {"traced_rays", st.traced_rays}, {"disoccluded", st.disoccluded},
        {"unreliable", st.unreliable}, {"curved", st.curved}, {"edge", st.edge},
        {"refined", st.refined}, {"learned", st.learned},
        {"invalid_offsets", st.invalid_offsets}, {"match_steps", st.match_steps},
        {"recompute_fraction", st.recompute_fraction()}, {"work", st.work},
        {"reflection_ms", st.reflection_ms()}});
    return named({{"color", image_array(std::move(color))},
        {"reflective", image_array<bool>(std::move(reflective))}, {"reuse", image_array(std::move(reuse))},
        {"stats", stats}});
  }

  int frames() const { return frames_; }

 private:
  std::shared_ptr<SceneHandle> handle_;
  ReflectionOptions reflection_;
  TemporalOptions temporal_;
  std::mutex mutex_;
  TemporalState state_;
  std::vector<vec3> reflected_;
  std::vector<uint8_t> flags_;
  int frames_ = 0;
};

std::unique_ptr<TemporalReflections> make_temporal(std::shared_ptr<SceneHandle> scene, float threshold,
                                                   int light_samples, int glossy_rays, uint64_t seed,
                                                   float stretch_limit, float spread_limit, float depth_discontinuity,
                                                   float curved_contrast, float edge_contrast,
                                                   const std::string& edge_rule, bool recompute_splats,
                                                   float blend_error, float keyframe_cost, bool match_extrapolate,
                                                   float lobe_seed_cell, float refine_error, float learn_error) {
  study::TemporalReflectOptions o;
  o.path = "-";  // the caller's cameras take the path's place; validate() asks for one
  o.threshold = threshold;
  o.light_samples = light_samples;
  o.glossy_rays = glossy_rays;
  o.seed = seed;
  o.stretch_limit = stretch_limit;
  o.spread_limit = spread_limit;
  o.depth_discontinuity = depth_discontinuity;
  o.curved_contrast = curved_contrast;
  o.edge_contrast = edge_contrast;
  o.edge_rule = edge_rule;
  o.recompute_splats = recompute_splats;
  o.blend_error = blend_error;
  o.keyframe_cost = keyframe_cost;
  o.match_extrapolate = match_extrapolate;
  o.lobe_seed_cell = lobe_seed_cell;
  o.refine_error = refine_error;
  o.learn_error = learn_error;
  return std::make_unique<TemporalReflections>(std::move(scene), o);
}

void bind_temporal(py::module_& m) {
  const study::TemporalReflectOptions d;
  py::class_<TemporalReflections>(
      m, "TemporalReflections",
      "Temporal reuse of reflections (thesis ch. 5, docs/temporal.md) as a stateful object: step(camera) renders "
      "the next frame, reusing the last key frame's reflections where it can and tracing the rest; the key-frame "
      "policy decides when a frame is traced in full. The options are `proxima reflect --method temporal`'s "
      "flags without --, '-' → '_' (threshold, light_samples, glossy_rays, seed, stretch_limit, spread_limit, "
      "depth_discontinuity, curved_contrast, edge_contrast, edge_rule, recompute_splats, blend_error, "
      "keyframe_cost, match_extrapolate, lobe_seed_cell, refine_error, learn_error). The scene's rest pose is used; one sample per pixel.")
      .def(py::init(&make_temporal), py::arg("scene"), py::kw_only(), py::arg("threshold") = d.threshold,
           py::arg("light_samples") = d.light_samples, py::arg("glossy_rays") = d.glossy_rays,
           py::arg("seed") = d.seed, py::arg("stretch_limit") = d.stretch_limit,
           py::arg("spread_limit") = d.spread_limit, py::arg("depth_discontinuity") = d.depth_discontinuity,
           py::arg("curved_contrast") = d.curved_contrast, py::arg("edge_contrast") = d.edge_contrast,
           py::arg("edge_rule") = d.edge_rule, py::arg("recompute_splats") = d.recompute_splats,
           py::arg("blend_error") = d.blend_error, py::arg("keyframe_cost") = d.keyframe_cost,
           py::arg("match_extrapolate") = d.match_extrapolate, py::arg("lobe_seed_cell") = d.lobe_seed_cell,
           py::arg("refine_error") = d.refine_error, py::arg("learn_error") = d.learn_error)
      .def("step", &TemporalReflections::step, py::arg("camera"),
           "Renders the next frame from `camera`; GIL released (steps of one object run one at a time). Returns "
           "a dict: color (H×W×3 float32 linear RGB, the frame: base + s·reflected), reflective (H×W bool, "
           "pixels of a reflective surface), reuse (H×W uint8, the reuse flags of reflective pixels: 0 reused, "
           "bit 0 disoccluded, bit 1 unreliable, bit 2 curved, bit 3 edge, bit 4 kept (the blend-error rule's, its reuse "
           "value observed), bit 5 refined, bit 6 learned — flagged pixels were traced), stats "
           "(dict: key, reflective, recomputed, rays, traced_rays, disoccluded, unreliable, curved, edge, refined, learned, "
           "invalid_offsets, match_steps, recompute_fraction, work, reflection_ms).")
      .def_property_readonly("frames", &TemporalReflections::frames, "Frames stepped so far.");
}

// Cluster reflections of one camera, and with `reference` Embree's answer for the same rays.
py::dict cluster_reflections_py(const SceneHandle& handle, const Camera& camera, int supersample, int glossy_rays,
                                int light_samples, uint64_t seed, int theta_bins, int phi_bins, float min_bin_scale,
                                float resolution_scale, bool second_layer, int march_block, bool reference) {
  study::ClusterReflectOptions o;
  o.width = camera.width;
  o.height = camera.height;
  o.reflection.supersample = supersample;
  o.reflection.glossy_rays = glossy_rays;
  o.reflection.area_light_samples = light_samples;
  o.reflection.seed = seed;
  o.cluster.clustering.max_theta_bins = theta_bins;
  o.cluster.clustering.max_phi_bins = phi_bins;
  o.cluster.clustering.min_bin_scale = min_bin_scale;
  o.cluster.resolution_scale = resolution_scale;
  o.cluster.second_layer = second_layer;
  o.cluster.march_block = march_block;
  study::validate(o);
  validate_camera(camera, "camera");
  check_image_budget("camera", uint64_t(camera.width) * uint64_t(supersample),
                     uint64_t(camera.height) * uint64_t(supersample), 24);
  if (reflective_objects(handle.scene()).empty())
    fail_input("scene: '" + handle.scene().name + "' has no reflective object");
  ImageF color, traced_color;
  ClusterFrameStats st;
  size_t samples = 0;
  {
    py::gil_scoped_release release;
    const auto lock = handle.read_lock();
    const Scene& scene = handle.scene();
    const std::vector<Bounds3> bounds = raster_object_bounds(scene);
    const ReflectionFrame frame = prepare_reflection_frame(scene, camera, o.reflection, bounds);
    TracedReflections traced;
    if (reference) traced = trace_reflections(scene, handle.rays(), frame);
    ClusterReflections c =
        render_cluster_reflections(scene, frame, o.cluster, bounds, reference ? &traced : nullptr);
    color = compose_reflections(frame, c.radiance);
    if (reference) traced_color = compose_reflections(frame, traced.radiance);
    st = c.stats;
    samples = frame.sample_count();
  }
  py::dict stats = named({{"reflective_samples", samples}, {"clusters", st.clusters}, {"texels", st.texels},
      {"rays", st.rays}, {"triangles_drawn", st.triangles_drawn}, {"shaded_texels", st.shaded_texels},
      {"env_fallback_samples", st.env_fallback_samples}, {"second_layer_texels", st.second_layer_texels},
      {"second_layer_rays", st.second_layer_rays}, {"planar_samples", st.planar_samples}});
  if (reference) {
    stats["occlusion_error_samples"] = st.occlusion_error_samples;
    stats["occlusion_error_rays"] = st.occlusion_error_rays;
  }
  py::dict out;
  out["color"] = image_array(std::move(color));
  if (reference) out["reference"] = image_array(std::move(traced_color));
  out["stats"] = stats;
  return out;
}

void bind_cluster(py::module_& m) {
  const study::ClusterReflectOptions d;
  m.def("cluster_reflections", &cluster_reflections_py, py::arg("scene"), py::arg("camera"), py::kw_only(),
        py::arg("supersample") = d.reflection.supersample, py::arg("glossy_rays") = d.reflection.glossy_rays,
        py::arg("light_samples") = d.reflection.area_light_samples, py::arg("seed") = d.reflection.seed,
        py::arg("theta_bins") = d.cluster.clustering.max_theta_bins,
        py::arg("phi_bins") = d.cluster.clustering.max_phi_bins,
        py::arg("min_bin_scale") = d.cluster.clustering.min_bin_scale,
        py::arg("resolution_scale") = d.cluster.resolution_scale, py::arg("second_layer") = d.cluster.second_layer,
        py::arg("march_block") = d.cluster.march_block, py::arg("reference") = false,
        "Reflections from clustered depth images (docs/cluster_reflections.md) on one camera, the scene's rest "
        "pose: the G-buffer at supersample×supersample samples per pixel, the reflective samples clustered, one "
        "depth image per cluster, every reflection ray marched through its cluster's image. Options as "
        "`proxima reflect --method cluster` (--ss = supersample, --gloss-rays, --light-samples, --seed, "
        "--theta-bins, --phi-bins, --min-bin-scale, --resolution-scale, --second-layer, --march-block). "
        "reference=True also traces the same rays with Embree. GIL released. Returns a dict: color (H×W×3 "
        "float32, linear RGB, base + s·reflected box-filtered over the samples), reference (the same with "
        "Embree's reflections, when asked), stats (dict: reflective_samples, clusters, texels, rays, "
        "triangles_drawn, shaded_texels, env_fallback_samples, second_layer_texels, second_layer_rays, "
        "planar_samples; with reference occlusion_error_samples, occlusion_error_rays).");
}

}  // namespace

void bind_techniques(py::module_& m) {
  bind_envmap(m);
  bind_temporal(m);
  bind_cluster(m);
}

}  // namespace proxima::python
