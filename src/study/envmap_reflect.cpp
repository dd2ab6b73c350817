// `proxima reflect` as a library call: env-map reflections (Wang et al. 2012, docs/envmap.md)
// beside the Embree reference with one mirror bounce, on the same camera and pixels.
#include "proxima/study/envmap_reflect.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/error.h"
#include "proxima/core/limits.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/reflect/box_probe.h"
#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/envmap_groups.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/envmap_set.h"
#include "proxima/reflect/reflection_comparison.h"
#include "proxima/scene/camera_path.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::study {

namespace {

bool is_method(const std::string& name) {
  return std::find(std::begin(kEnvmapReflectMethods), std::end(kEnvmapReflectMethods), name) !=
         std::end(kEnvmapReflectMethods);
}

std::vector<std::string> methods_of(const EnvmapReflectOptions& o) {
  if (o.compare) return {std::begin(kEnvmapReflectMethods), std::end(kEnvmapReflectMethods)};
  return {o.method};
}

// Animated objects at the time of the chosen path frame (as `proxima render`), else at 0.
std::optional<Scene> posed_scene(const Scene& scene, const CameraChoice& choice) {
  if (!has_animation(scene)) return std::nullopt;
  float t = 0.0f;
  const int p = choice.path.empty() ? -1 : find_camera_path(scene, choice.path);
  if (p >= 0) t = frame_time(scene.camera_paths[size_t(p)], choice.frame);
  return pose_scene(scene, t);
}

// The maps' memory: per face texel 4 floats (color, distance), 1 float (distance again),
// 1 object id; 6 faces per map; per group one map for the single-map methods and K layers.
void check_map_budget(const EnvmapReflectOptions& o, uint64_t groups) {
  const std::vector<std::string> methods = methods_of(o);
  const bool single = std::any_of(methods.begin(), methods.end(),
                                  [](const std::string& m) { return m != "layered" && m != "reference"; });
  const bool layered = std::find(methods.begin(), methods.end(), "layered") != methods.end();
  const uint64_t maps = groups * (uint64_t(single) + (layered ? uint64_t(o.layers) : 0));
  check_image_budget("--cube-size", uint64_t(o.cube_size), uint64_t(o.cube_size), 36 * maps);
}

double pct(size_t part, size_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; }

// With more than one reflector: how they were grouped (one map per group).
void report_groups(const std::vector<EnvmapGroup>& groups, Results& results) {
  results.metrics["maps"] = double(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::string key = "map" + std::to_string(g) + "_";
    results.metrics[key + "reflectors"] = double(groups[g].reflectors.size());
    results.metrics[key + "radius_m"] = groups[g].radius;
    results.metrics[key + "parallax"] = groups[g].parallax;
  }
}

// The maps the methods read (envmap_set.h), built once (a static environment) and timed
// apart from the per-frame work (build times summed over the groups).
EnvmapSet build_maps(const Scene& scene, const RayScene& rays, const std::vector<uint32_t>& reflectors,
                     const EnvmapReflectOptions& o, const std::vector<std::string>& methods, Results& results) {
  auto wants = [&](const char* m) { return std::find(methods.begin(), methods.end(), m) != methods.end(); };
  EnvmapSetOptions so;
  so.grouping = {o.group_parallax, o.max_maps};
  so.map.resolution = o.cube_size;
  so.map.area_light_samples = o.light_samples;
  so.map.seed = o.seed;
  so.single = wants("envmap") || wants("rectified") || wants("average") || wants("boxprobe");
  so.average_step_rad = glm::radians(o.angle_step_deg);
  so.layers = wants("layered") ? o.layers : 0;
  const EnvmapSet set = build_envmap_set(scene, rays, reflectors, so);
  results.metrics["envmap_group_ms"] = set.group_ms;
  if (reflectors.size() > 1) report_groups(set.groups, results);
  if (so.single) {
    results.metrics["envmap_build_ms"] = set.map_ms;
    results.metrics["average_distance_ms"] = set.average_ms;
    results.metrics["average_distance_m"] = set.maps[0].average_distance;
  }
  if (so.layers > 0) {
    double layers = 0.0;
    float radius = 0.0f;
    std::vector<double> shaded, hidden;
    for (size_t g = 0; g < set.groups.size(); ++g) {
      radius = std::max(radius, set.groups[g].radius);
      const std::vector<DistanceCubeMap>& l = set.maps[g].layers;
      layers = std::max(layers, double(l.size()));
      shaded.resize(std::max(shaded.size(), l.size()), 0.0);
      hidden.resize(shaded.size(), 0.0);
      for (size_t k = 0; k < l.size(); ++k) {
        shaded[k] += double(l[k].shaded_texels);
        hidden[k] += double(l[k].hidden_texels);
      }
    }
    results.metrics["layered_build_ms"] = set.layers_ms;
    results.metrics["layers"] = layers;
    results.metrics["viewer_radius_m"] = radius;
    for (size_t k = 0; k < shaded.size(); ++k) {
      results.metrics["layer" + std::to_string(k) + "_shaded_texels"] = shaded[k];
      results.metrics["layer" + std::to_string(k) + "_hidden_texels"] = hidden[k];
    }
  }
  return set;
}


// The pixels a method is judged on: where both its rasterized reflector and the reference
// see a reflector (`mask`), and of those the ones whose mirror ray meets the environment,
// not a reflector (`env_mask`), with the object the reference's mirror ray meets.
struct Judged {
  ReflectorPixels pixels;
  PixelMask mask, env_mask;
  ImageU32 reference_objects;
};

// `compared` without the pixels whose reference mirror ray meets a reflector of the pixel's
// own group: its map leaves those out (the other groups' reflectors are in it).
PixelMask group_environment_mask(const Scene& scene, const PixelMask& compared, const ReflectorPixels& pixels,
                                 const ImageU32& reference_objects, const EnvmapSet& maps) {
  PixelMask out{compared.mask, 0};
  for (size_t i = 0; i < out.mask.data().size(); ++i) {
    uint8_t& m = out.mask.data()[i];
    if (!m) continue;
    const uint32_t t = pixels.triangle.data()[i], hit = reference_objects.data()[i];
    const uint32_t g = t == kNoTriangle ? kNoEnvmapGroup : maps.group_of[scene.triangle_object[t]];
    if (g != kNoEnvmapGroup && hit < maps.group_of.size() && maps.group_of[hit] == g) m = 0;
    out.pixels += m != 0;
  }
  return out;
}

Judged judged_pixels(const Scene& scene, const RayScene& rays, const Camera& camera, const ItemBuffer& item,
                     const std::vector<uint32_t>& reflectors, const EnvmapSet& maps, Results& results) {
  Judged j;
  j.pixels = rasterize_reflector_pixels(scene, camera, reflectors);
  j.mask = comparison_mask(j.pixels.triangle, item, scene, reflectors);
  results.metrics["reflector_pixels"] = double(j.mask.pixels);
  j.reference_objects = reference_reflected_objects(scene, rays, camera, item, j.mask.mask);
  j.env_mask = group_environment_mask(scene, j.mask, j.pixels, j.reference_objects, maps);
  results.metrics["self_reflection_pct"] = pct(j.mask.pixels - j.env_mask.pixels, j.mask.pixels);
  return j;
}

// Each method's outputs (and warm-up) first, then the timed frames round-robin over the
// methods, so load changes on a shared machine hit every method alike. A method's frame is
// the reflector's visibility (rasterized) and its shading; the reference's is a full render.
struct Frames {
  std::vector<EnvmapFrame> frames;
  std::vector<double> median_ms;
};

Frames render_frames(const Scene& scene, const RayScene& rays, const Camera& camera,
                     const std::vector<uint32_t>& reflectors, EnvmapInputs in, const ReferenceOptions& ro,
                     const std::vector<std::string>& methods, int reps, Progress* progress) {
  auto frame_of = [&](const std::string& m) {
    in.method = parse_envmap_method(m);
    return shade_reflector_pixels(scene, rays, camera, rasterize_reflector_pixels(scene, camera, reflectors), in);
  };
  Frames out;
  out.frames.resize(methods.size());
  for (size_t i = 0; i < methods.size(); ++i)
    if (methods[i] != "reference") out.frames[i] = frame_of(methods[i]);
  std::vector<std::vector<double>> times(methods.size());
  for (int r = 0; r < reps; ++r) {
    if (progress) progress->step("timing " + std::to_string(r + 1) + "/" + std::to_string(reps));
    for (size_t i = 0; i < methods.size(); ++i) {
      Stopwatch w;
      if (methods[i] == "reference")
        render_reference(scene, rays, camera, ro);
      else
        frame_of(methods[i]);
      times[i].push_back(w.elapsed_ms());
    }
  }
  for (const auto& t : times) out.median_ms.push_back(median(t));
  return out;
}

// The frame's image: the reference outside the reflector, the method's shading on it (only
// the reflection differs).
ImageF composite(const ImageF& reference, const ReflectorPixels& pixels, const EnvmapFrame& frame) {
  ImageF color = reference;
  for (int y = 0; y < color.height(); ++y)
    for (int x = 0; x < color.width(); ++x)
      if (pixels.triangle.at(x, y) != kNoTriangle)
        for (int c = 0; c < 3; ++c) color.at(x, y, c) = frame.color.at(x, y, c);
  return color;
}

std::string table_title(const Scene& scene, const Camera& camera, const EnvmapReflectOptions& o) {
  return "reflect " + scene.name + " (" + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
         ", cube " + std::to_string(o.cube_size) + "², d_e " + std::to_string(o.d_e).substr(0, 5) + ")";
}

// One method's metrics, images and table row.
void report_method(const std::string& m, const EnvmapFrame& frame, double ms, const ImageF& reference,
                   const Judged& j, const StudyOutput& out, Results& results, Table& table) {
  double with_build = ms, edge_pct = 0.0, match_pct = 100.0;
  ImageF color = reference;
  if (m != "reference") {
    with_build += results.metrics[m == "layered" ? "layered_build_ms" : "envmap_build_ms"];
    const EnvmapStats& st = frame.stats;
    edge_pct = pct(st.edge_lookups, st.lookups);
    results.metrics[m + "_edge_pct"] = edge_pct;
    if (m == "layered") results.metrics["layered_fallback_pct"] = pct(st.fallback_lookups, st.lookups);
    match_pct = object_match_pct(frame.object, j.reference_objects, j.mask);
    results.metrics[m + "_samples_per_lookup"] = st.lookups ? double(st.map_samples) / double(st.lookups) : 0.0;
    color = composite(reference, j.pixels, frame);
  }
  // eval/image_error.h: 0–255 on the displayed sRGB scale, channels averaged.
  const double mae = compare_images(color, reference, &j.mask.mask).mae_avg;
  const double env_mae = compare_images(color, reference, &j.env_mask.mask).mae_avg;
  results.metrics[m + "_mae"] = mae;
  results.metrics[m + "_env_mae"] = env_mae;
  results.metrics[m + "_ms"] = ms;
  results.metrics[m + "_with_build_ms"] = with_build;
  results.metrics[m + "_object_match_pct"] = match_pct;
  write_image(out, results, m, m + ".png", color);
  if (m != "reference")
    write_image(out, results, "error_" + m, "error_" + m + ".png",
                error_heatmap(error_image(color, reference, &j.mask.mask), kErrorHeatmapMax, &j.mask.mask));
  table.rows.push_back({m, ms, 1000.0 / ms, with_build, mae, env_mae, match_pct, edge_pct});
}

// The proxy box the boxprobe method projected onto.
void report_box(const Bounds3& box, Results& results) {
  const char* axis[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    results.metrics[std::string("probe_box_min_") + axis[a]] = box.min[a];
    results.metrics[std::string("probe_box_max_") + axis[a]] = box.max[a];
  }
}

}  // namespace

EnvmapInputs envmap_inputs(const Scene& scene, const EnvmapReflectOptions& o) {
  EnvmapInputs in;
  in.method = parse_envmap_method(o.method == "reference" ? "rectified" : o.method);
  in.rectify.D = o.distance > 0.0f ? o.distance : scene_bounds(scene).diagonal();
  in.rectify.d_e = o.d_e;
  in.rectify.edge = o.edge == "fallback" ? EdgeRule::PlainFallback : EdgeRule::Black;
  in.rectify.max_march_steps = o.march_steps;
  in.box = probe_proxy_box(scene);
  in.area_light_samples = o.light_samples;
  in.glossy_rays = o.glossy_rays;
  in.seed = o.seed;
  return in;
}

void validate(const EnvmapReflectOptions& o) {
  if (!is_method(o.method))
    fail_input("--method: '" + o.method + "' is not one of envmap, rectified, average, layered, boxprobe, reference");
  if (!(o.d_e > 0.0f) || !std::isfinite(o.d_e)) fail_input("--d-e: must be a positive number");
  if (!(o.distance >= 0.0f) || !std::isfinite(o.distance))
    fail_input("--distance: must be ≥ 0 (0 = scene diagonal)");
  require_in_range(o.cube_size, 1, kMaxImageSide, "--cube-size");
  require_above_at_most(o.angle_step_deg, 0.0f, 90.0f, "--angle-step", "degrees");
  if (o.edge != "black" && o.edge != "fallback") fail_input("--edge: must be black or fallback");
  require_in_range(o.light_samples, 1, 64, "--light-samples");
  require_in_range(o.glossy_rays, 1, 4096, "--glossy-rays");
  require_in_range(o.reps, 1, 100, "--reps");
  require_in_range(o.layers, 1, kMaxDistanceCubeLayers, "--layers");
  require_in_range(o.march_steps, 1, 4096, "--march-steps");
  check_map_budget(o, 1);
  validate(EnvmapGroupOptions{o.group_parallax, o.max_maps});
}

void validate(const EnvmapReflectOptions& o, const Scene& scene) {
  validate(o);
  pick_camera(scene, o.camera, o.width, o.height);
  // Posing moves objects, it never changes their materials.
  const size_t reflectors = reflective_objects(scene).size();
  if (reflectors == 0) fail_input("--scene: '" + scene.name + "' has no reflective object");
  check_map_budget(o, std::min<uint64_t>(reflectors, uint64_t(o.max_maps)));  // a set of maps per group
}

Results run_envmap_reflect(const Scene& input, const EnvmapReflectOptions& o, const StudyOutput& out,
                           Progress* progress) {
  validate(o, input);
  const Camera camera = pick_camera(input, o.camera, o.width, o.height);
  const std::optional<Scene> posed = posed_scene(input, o.camera);
  const Scene& scene = posed ? *posed : input;
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  const std::vector<std::string> methods = methods_of(o);
  if (progress) progress->begin("reflect", 3 + o.reps);

  Results results;
  if (progress) progress->step("reference");
  RayScene rays(scene);
  // The reference: the same camera and pixels, mirror rays one bounce deep.
  ReferenceOptions ro;
  ro.area_light_samples = o.light_samples;
  ro.glossy_rays = o.glossy_rays;
  ro.max_bounces = 1;
  ro.seed = o.seed;
  const ImageF reference = render_reference(scene, rays, camera, ro);
  const ItemBuffer item = trace_item_buffer(scene, rays, camera);

  if (progress) progress->step("maps");
  const EnvmapSet maps = build_maps(scene, rays, reflectors, o, methods, results);
  const EnvmapInputs in = with_envmap_set(envmap_inputs(scene, o), maps);
  results.metrics["D_m"] = in.rectify.D;
  results.metrics["d_e_m"] = o.d_e;
  results.metrics["N"] = rectify_step_limit(in.rectify.D, o.d_e);
  if (std::find(methods.begin(), methods.end(), "boxprobe") != methods.end()) report_box(in.box, results);
  const Judged judged = judged_pixels(scene, rays, camera, item, reflectors, maps, results);

  if (progress) progress->step("frames");
  const Frames frames = render_frames(scene, rays, camera, reflectors, in, ro, methods, o.reps, progress);
  Table table{table_title(scene, camera, o),
              {"method", "ms_per_frame", "fps", "ms_with_map_build", "mae_0_255", "env_mae_0_255",
               "object_match_pct", "edge_pct"},
              {}};
  for (size_t i = 0; i < methods.size(); ++i)
    report_method(methods[i], frames.frames[i], frames.median_ms[i], reference, judged, out, results, table);
  results.tables.push_back(std::move(table));
  if (progress) progress->end();
  return results;
}

}  // namespace proxima::study
