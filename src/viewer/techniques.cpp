#include "proxima/viewer/techniques.h"

#include <algorithm>
#include <optional>

#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/box_probe.h"
#include "proxima/reflect/cluster_reflection.h"
#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/envmap_frame_reflections.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/envmap_set.h"
#include "proxima/reflect/ssr_reflection.h"
#include "proxima/reflect/temporal_reuse.h"
#include "proxima/trace/reference_renderer.h"
#include "gibr_technique.h"
#include "shadow_technique.h"

namespace proxima {

namespace {

// What the reflection techniques share: the reflectors, object bounds for culling, the
// env maps per group of reflectors and the box probe's map (each built on first use, as
// `proxima reflect` builds them once).
// A technique's options with the viewer's seed.
template <typename Options>
Options seeded(Options o, uint64_t seed) {
  o.seed = seed;
  return o;
}

struct ReflectionShared {
  TechniqueSettings settings;  // the live knobs; the parameter keys change them
  std::vector<uint32_t> reflectors;
  std::vector<Bounds3> bounds;
  std::optional<EnvmapSet> maps;
  std::optional<DistanceCubeMap> probe;
  RectifyOptions rectify;
};

ImageF shaded_reference(const ViewerScene& vs, const TechniqueSettings& s, const Camera& camera, int row_begin,
                        int row_end) {
  ReferenceOptions o = seeded(s.reference, s.seed);
  o.row_begin = row_begin;
  o.row_end = row_end;
  return render_reference(vs.scene, vs.rays, camera, o);
}

// The G-buffer pass every reflection technique starts from (its diffuse shading is the
// "base" the reflections blend into).
ReflectionFrame gbuffer(const ViewerScene& vs, const ReflectionShared& shared, const TechniqueSettings& s,
                        const Camera& camera, std::vector<StepTime>& steps) {
  Stopwatch w;
  ReflectionFrame frame = prepare_reflection_frame(vs.scene, camera, seeded(s.reflection, s.seed), shared.bounds);
  steps.push_back({"g-buffer + diffuse", w.elapsed_ms()});
  return frame;
}

ImageF compose(const ReflectionFrame& frame, const std::vector<vec3>& reflected, std::vector<StepTime>& steps) {
  Stopwatch w;
  ImageF color = compose_reflections(frame, reflected);
  steps.push_back({"compose", w.elapsed_ms()});
  return color;
}

DistanceCubeMapOptions cube_map_options(const TechniqueSettings& s) {
  DistanceCubeMapOptions mo;
  mo.resolution = s.cube_size;
  mo.area_light_samples = s.reflection.area_light_samples;
  mo.seed = s.seed;
  return mo;
}

const EnvmapSet& envmap_set(const ViewerScene& vs, ReflectionShared& shared, const TechniqueSettings& s,
                            std::vector<StepTime>& steps) {
  if (!shared.maps) {
    EnvmapSetOptions so;
    so.map = cube_map_options(s);
    Stopwatch w;
    shared.maps = build_envmap_set(vs.scene, vs.rays, shared.reflectors, so);
    steps.push_back({"cube maps build (once)", w.elapsed_ms()});
  }
  return *shared.maps;
}

// The box probe: one map for the room, around every reflector's center with all left out.
const DistanceCubeMap& probe_map(const ViewerScene& vs, ReflectionShared& shared, const TechniqueSettings& s,
                                 std::vector<StepTime>& steps) {
  if (!shared.probe) {
    DistanceCubeMapOptions mo = cube_map_options(s);
    mo.exclude = shared.reflectors;
    Stopwatch w;
    shared.probe = render_distance_cube_map(vs.scene, vs.rays, projection_center(vs.scene, shared.reflectors), mo);
    steps.push_back({"probe cube map build (once)", w.elapsed_ms()});
  }
  return *shared.probe;
}

Technique envmap_technique(std::shared_ptr<ViewerScene> vs, std::shared_ptr<ReflectionShared> shared,
                           EnvmapMethod method) {
  Technique t;
  t.name = envmap_method_name(method);
  t.label = method == EnvmapMethod::Plain ? "env map" : "rectified env map";
  t.render = [vs, shared, method](const Camera& camera) {
    const TechniqueSettings& s = shared->settings;
    TechniqueFrame out;
    EnvmapInputs in;
    in.method = method;
    in.rectify = shared->rectify;
    in = with_envmap_set(in, envmap_set(*vs, *shared, s, out.steps));
    const ReflectionFrame frame = gbuffer(*vs, *shared, s, camera, out.steps);
    Stopwatch w;
    const std::vector<vec3> reflected = envmap_frame_reflections(vs->scene, frame, in);
    out.steps.push_back({"env map lookups", w.elapsed_ms()});
    out.color = compose(frame, reflected, out.steps);
    return out;
  };
  return t;
}

// The engines' baselines: the box-projected probe alone, and SSR falling back to it.
Technique baseline_technique(std::shared_ptr<ViewerScene> vs, std::shared_ptr<ReflectionShared> shared, bool ssr) {
  Technique t;
  t.name = ssr ? "ssr" : "boxprobe";
  t.label = ssr ? "screen-space reflections + box probe" : "box-projected env map";
  t.render = [vs, shared, ssr](const Camera& camera) {
    const TechniqueSettings& s = shared->settings;
    TechniqueFrame out;
    const DistanceCubeMap& map = probe_map(*vs, *shared, s, out.steps);
    const ReflectionFrame frame = gbuffer(*vs, *shared, s, camera, out.steps);
    const Bounds3 box = probe_proxy_box(vs->scene);
    std::vector<vec3> reflected;
    if (ssr) {
      SsrReflections r = render_ssr_reflections(vs->scene, frame, {}, {&map, box}, shared->bounds);
      const double depth_ms = r.stats.gbuffer_ms + r.stats.backface_ms + r.stats.pyramid_ms;
      out.steps.emplace_back(StepTime{"ssr depth passes", depth_ms});
      out.steps.emplace_back(StepTime{"ssr trace+fallback", r.stats.trace_ms});
      reflected = std::move(r.radiance);
    } else {
      Stopwatch w;
      EnvmapInputs in;
      in.method = EnvmapMethod::BoxProbe;
      in.map = &map;
      in.box = box;
      reflected = envmap_frame_reflections(vs->scene, frame, in);
      out.steps.push_back({"box probe lookups", w.elapsed_ms()});
    }
    out.color = compose(frame, reflected, out.steps);
    return out;
  };
  return t;
}

Technique cluster_technique(std::shared_ptr<ViewerScene> vs, std::shared_ptr<ReflectionShared> shared) {
  Technique t;
  t.name = "cluster";
  t.label = "cluster reflections";
  t.render = [vs, shared](const Camera& camera) {
    const TechniqueSettings& s = shared->settings;
    TechniqueFrame out;
    const ReflectionFrame frame = gbuffer(*vs, *shared, s, camera, out.steps);
    const ClusterReflections cr = render_cluster_reflections(vs->scene, frame, {}, shared->bounds);
    out.steps.push_back({"clustering", cr.stats.clustering_ms});
    out.steps.push_back({"cluster cameras", cr.stats.cameras_ms});
    out.steps.push_back({"depth images", cr.stats.depth_images_ms});
    out.steps.push_back({"intersection", cr.stats.intersection_ms});
    out.color = compose(frame, cr.radiance, out.steps);
    return out;
  };
  return t;
}

Technique temporal_technique(std::shared_ptr<ViewerScene> vs, std::shared_ptr<ReflectionShared> shared) {
  struct State {
    TemporalState temporal;
    int width = 0, height = 0;
  };
  auto state = std::make_shared<State>();
  Technique t;
  t.name = "temporal";
  t.label = "temporal reuse";
  t.render = [vs, shared, state](const Camera& camera) {
    const TechniqueSettings& s = shared->settings;
    // The key frame's reflection depth image is per resolution: a new size starts over.
    if (camera.width != state->width || camera.height != state->height) *state = {{}, camera.width, camera.height};
    TechniqueFrame out;
    const ReflectionFrame frame = gbuffer(*vs, *shared, s, camera, out.steps);
    TemporalFrameStats st;
    const std::vector<vec3> reflected = temporal_reflections(vs->scene, vs->rays, frame, state->temporal, {}, &st);
    if (st.key) out.steps.push_back({"key frame trace", st.key_ms});
    out.steps.push_back({"best match", st.match_ms});
    out.steps.push_back({"offset warp", st.warp_ms});
    out.steps.push_back({"reprojection", st.reproject_ms});
    out.steps.push_back({"recompute", st.recompute_ms});
    out.color = compose(frame, reflected, out.steps);
    return out;
  };
  t.reset = [state] { *state = {}; };
  return t;
}

}  // namespace

std::vector<Technique> make_techniques(std::shared_ptr<ViewerScene> vs, const TechniqueSettings& s) {
  auto shared = std::make_shared<ReflectionShared>();
  shared->settings = s;
  shared->reflectors = reflective_objects(vs->scene);
  shared->bounds = raster_object_bounds(vs->scene);
  shared->rectify.D = scene_bounds(vs->scene).diagonal();

  // Parameter keys: doubling / halving one knob per technique, within bounds.
  // `field` is a knob in shared->settings, which the returned function keeps alive.
  auto knob = [shared](const char* what, int* field, int lo, int hi, bool drop_map) {
    return [shared, what, field, lo, hi, drop_map](int step) {
      int& v = *field;
      v = std::clamp(step > 0 ? v * 2 : v / 2, lo, hi);
      if (drop_map) {
        shared->maps.reset();
        shared->probe.reset();
      }
      return std::string(what) + " " + std::to_string(v);
    };
  };
  std::vector<Technique> list;
  Technique reference;
  reference.adjust = knob("area-light samples n (n x n)", &shared->settings.live.area_light_samples, 1, 16, false);
  reference.name = "reference";
  reference.label = "reference ray tracing";
  reference.render = [vs, shared](const Camera& camera) {
    TechniqueFrame out;
    Stopwatch w;
    out.color = render_reference(vs->scene, vs->rays, camera, seeded(shared->settings.live, shared->settings.seed));
    out.steps.push_back({"trace", w.elapsed_ms()});
    return out;
  };
  list.push_back(reference);
  list.push_back(envmap_technique(vs, shared, EnvmapMethod::Plain));
  list.push_back(envmap_technique(vs, shared, EnvmapMethod::Rectified));
  list.push_back(cluster_technique(vs, shared));
  list.push_back(temporal_technique(vs, shared));
  for (size_t i = 1; i < list.size(); ++i)
    list[i].adjust = i <= 2 ? knob("cube map faces", &shared->settings.cube_size, 16, 2048, true)
                            : knob("glossy lobe rays", &shared->settings.reflection.glossy_rays, 1, 64, false);
  if (shared->reflectors.empty())
    for (Technique& t : list)
      if (t.name != "reference") t.unavailable = "the scene has no reflective object";
  list.push_back(shadow_technique(vs, s));

  list.push_back(gibr_technique(vs, s));
  // Appended so the keys above stay; both read the shared cube map.
  for (bool ssr : {false, true}) {
    Technique b = baseline_technique(vs, shared, ssr);
    b.adjust = knob("cube map faces", &shared->settings.cube_size, 16, 2048, true);
    if (shared->reflectors.empty()) b.unavailable = "the scene has no reflective object";
    list.push_back(b);
  }

  for (size_t i = 0; i < list.size(); ++i) {
    list[i].key = char('1' + i);
    if (!list[i].reference)
      list[i].reference = [vs, s](const Camera& camera, int row_begin, int row_end) {
        return shaded_reference(*vs, s, camera, row_begin, row_end);
      };
  }
  return list;
}

}  // namespace proxima
