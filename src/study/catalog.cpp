// The study catalog: one field table per options struct (name, member path, doc), with the
// conversion between OptionValue and each member type written once per type (Codec<T>), not
// once per field.
#include "proxima/study/catalog.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

#include "proxima/core/error.h"
#include "proxima/study/cluster_reflect.h"
#include "proxima/study/envmap_reflect.h"
#include "proxima/study/gibr.h"
#include "proxima/study/raster_bench.h"
#include "proxima/study/reference.h"
#include "proxima/study/sampling.h"
#include "proxima/study/shadows.h"
#include "proxima/study/technique_bench.h"
#include "proxima/study/temporal_reflect.h"
#include "proxima/study/trace_bench.h"
#include "proxima/study/visibility.h"

namespace proxima::study {

namespace {

const char* type_of(const OptionValue& v) {
  static constexpr const char* kNames[] = {"bool", "int", "float", "string"};
  return kNames[v.index()];
}

[[noreturn]] void fail_type(const std::string& name, const char* expected, const OptionValue& v) {
  fail_input("option '" + name + "': expected " + expected + ", got " + type_of(v) + " " + option_text(v));
}

// Conversion of one member type: its catalog type name, its value, and a value parsed back
// (InputError naming the option for the wrong type or an out-of-range number).
template <typename T>
struct Codec;

template <>
struct Codec<bool> {
  static constexpr const char* type = "bool";
  static OptionValue to(bool b) { return b; }
  static bool from(const OptionValue& v, const std::string& name) {
    if (const bool* b = std::get_if<bool>(&v)) return *b;
    fail_type(name, type, v);
  }
  static std::vector<std::string> choices() { return {}; }
};

template <typename I>
  requires(std::is_integral_v<I> && !std::is_same_v<I, bool>)
struct Codec<I> {
  static constexpr const char* type = "int";
  static OptionValue to(I i) { return static_cast<std::int64_t>(i); }
  static I from(const OptionValue& v, const std::string& name) {
    const std::int64_t* i = std::get_if<std::int64_t>(&v);
    if (!i) fail_type(name, type, v);
    if (!std::in_range<I>(*i))
      fail_input("option '" + name + "': " + std::to_string(*i) + " is out of range (" +
                 std::to_string(std::numeric_limits<I>::min()) + ".." + std::to_string(std::numeric_limits<I>::max()) +
                 ")");
    return static_cast<I>(*i);
  }
  static std::vector<std::string> choices() { return {}; }
};

// Also from an int, and from "inf" / "-inf" (JSON manifests have no infinity).
template <typename F>
  requires std::is_floating_point_v<F>
struct Codec<F> {
  static constexpr const char* type = "float";
  static OptionValue to(F f) { return static_cast<double>(f); }
  static F from(const OptionValue& v, const std::string& name) {
    double d = 0.0;
    if (const double* x = std::get_if<double>(&v)) d = *x;
    else if (const std::int64_t* i = std::get_if<std::int64_t>(&v)) d = static_cast<double>(*i);
    else if (const std::string* s = std::get_if<std::string>(&v); s && (*s == "inf" || *s == "-inf"))
      d = *s == "inf" ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    else fail_type(name, "float (or \"inf\")", v);
    if (std::isnan(d) || (std::isfinite(d) && std::fabs(d) > std::numeric_limits<F>::max()))
      fail_input("option '" + name + "': " + option_text(v) + " is not a representable number");
    return static_cast<F>(d);
  }
  static std::vector<std::string> choices() { return {}; }
};

template <>
struct Codec<std::string> {
  static constexpr const char* type = "string";
  static OptionValue to(const std::string& s) { return s; }
  static std::string from(const OptionValue& v, const std::string& name) {
    if (const std::string* s = std::get_if<std::string>(&v)) return *s;
    fail_type(name, type, v);
  }
  static std::vector<std::string> choices() { return {}; }
};

template <>
struct Codec<std::filesystem::path> {
  static constexpr const char* type = "string";
  static OptionValue to(const std::filesystem::path& p) { return p.string(); }
  static std::filesystem::path from(const OptionValue& v, const std::string& name) {
    return Codec<std::string>::from(v, name);
  }
  static std::vector<std::string> choices() { return {}; }
};

// An enum by the names of its own name/parse functions (which name the option on error).
template <typename E, auto kValues, auto Name, auto Parse>
struct EnumCodec {
  static constexpr const char* type = "string";
  static OptionValue to(E e) { return std::string(Name(e)); }
  static E from(const OptionValue& v, const std::string& name) {
    return Parse(Codec<std::string>::from(v, name), ("option '" + name + "'").c_str());
  }
  static std::vector<std::string> choices() {
    std::vector<std::string> names;
    for (E e : kValues) names.push_back(Name(e));
    return names;
  }
};

constexpr std::array kSamplingMethods{SamplingMethod::Conventional, SamplingMethod::Peeling, SamplingMethod::NrrPixel,
                                      SamplingMethod::NrrVisibility};
constexpr std::array kShadowSamplings{ShadowSampling::Nrr, ShadowSampling::Conventional, ShadowSampling::Peeling,
                                      ShadowSampling::Geometry};
constexpr std::array kRedundancies{Redundancy::Pixel, Redundancy::Visibility};
constexpr std::array kReconstructions{ReconstructionMethod::Hybrid, ReconstructionMethod::Conventional};
constexpr std::array kViewShapes{ViewShape::Segment, ViewShape::Triangle, ViewShape::Rectangle};
constexpr std::array kGibrViews{GibrViews::Path, GibrViews::Offpath, GibrViews::Photos};

template <>
struct Codec<SamplingMethod>
    : EnumCodec<SamplingMethod, kSamplingMethods, sampling_method_name, parse_sampling_method> {};
template <>
struct Codec<ShadowSampling>
    : EnumCodec<ShadowSampling, kShadowSamplings, shadow_sampling_name, parse_shadow_sampling> {};
template <>
struct Codec<Redundancy> : EnumCodec<Redundancy, kRedundancies, redundancy_name, parse_redundancy> {};
template <>
struct Codec<ReconstructionMethod>
    : EnumCodec<ReconstructionMethod, kReconstructions, reconstruction_name, parse_reconstruction> {};
template <>
struct Codec<ViewShape> : EnumCodec<ViewShape, kViewShapes, view_shape_name, parse_view_shape> {};
template <>
struct Codec<GibrViews> : EnumCodec<GibrViews, kGibrViews, gibr_views_name, parse_gibr_views> {};

// A list of enums: the names comma-separated, as the flag takes them; at least one.
template <typename E>
struct Codec<std::vector<E>> {
  static constexpr const char* type = "string";
  static OptionValue to(const std::vector<E>& list) {
    std::string text;
    for (E e : list) {
      if (!text.empty()) text += ',';
      text += std::get<std::string>(Codec<E>::to(e));
    }
    return text;
  }
  static std::vector<E> from(const OptionValue& v, const std::string& name) {
    const std::string text = Codec<std::string>::from(v, name);
    std::vector<E> list;
    for (size_t begin = 0; begin <= text.size();) {
      const size_t end = std::min(text.find(',', begin), text.size());
      list.push_back(Codec<E>::from(text.substr(begin, end - begin), name));
      begin = end + 1;
    }
    return list;
  }
  static std::vector<std::string> choices() { return Codec<E>::choices(); }
};

// An optional enum: "" = none (the study's default rule).
template <typename E>
struct Codec<std::optional<E>> {
  static constexpr const char* type = "string";
  static OptionValue to(const std::optional<E>& e) { return e ? Codec<E>::to(*e) : OptionValue(std::string()); }
  static std::optional<E> from(const OptionValue& v, const std::string& name) {
    if (Codec<std::string>::from(v, name).empty()) return std::nullopt;
    return Codec<E>::from(v, name);
  }
  static std::vector<std::string> choices() { return Codec<E>::choices(); }
};

// The member at the end of a chain of member pointers: member(o, &A::b, &B::c) is o.b.c.
template <typename O, typename M>
auto& member(O& o, M m) {
  return o.*m;
}
template <typename O, typename M, typename... Ms>
auto& member(O& o, M m, Ms... rest) {
  return member(o.*m, rest...);
}

template <typename O>
struct Field {
  OptionInfo info;
  std::function<void(O&, const OptionValue&)> set;
  std::function<OptionValue(const O&)> get;
};

// One option: its name, its doc and the member it sets, reached through `chain`.
template <typename O, typename... Ms>
Field<O> field(const char* name, const char* doc, Ms... chain) {
  using T = std::remove_cvref_t<decltype(member(std::declval<O&>(), chain...))>;
  const O defaults{};
  Field<O> f;
  f.info = OptionInfo{name, Codec<T>::type, doc, Codec<T>::to(member(defaults, chain...)), Codec<T>::choices()};
  f.set = [name = std::string(name), chain...](O& o, const OptionValue& v) {
    member(o, chain...) = Codec<T>::from(v, name);
  };
  f.get = [chain...](const O& o) { return Codec<T>::to(member(o, chain...)); };
  return f;
}

// --camera, --path, --frame of a CameraChoice member.
template <typename O>
void add_camera_fields(std::vector<Field<O>>& fields, CameraChoice O::*choice) {
  fields.push_back(field<O>("camera", "scene camera, by index or name; empty = the first", choice,
                            &CameraChoice::camera));
  fields.push_back(field<O>("path", "camera path, by index or name; empty = none (the camera)", choice,
                            &CameraChoice::path));
  fields.push_back(field<O>("frame", "frame on the camera path (0-based)", choice, &CameraChoice::frame));
}

// A study behind type erasure: options applied from values, then run.
struct Entry {
  StudyInfo info;
  std::function<OptionValues(const OptionValues&)> resolve;
  std::function<Results(const Scene&, const OptionValues&, const StudyOutput&, Progress*)> run;
  // A study that splits into frame parts (study/frame_split.h): a part, and the results
  // from every part's figures; empty for the others.
  std::function<Results(const Scene&, const OptionValues&, const FramePart&, const StudyOutput&, FrameFigures&,
                        Progress*)>
      run_part;
  std::function<Results(const Scene&, const OptionValues&, const FrameFigures&)> part_results;
};

template <typename O>
O apply_options(const std::string& study, const std::vector<Field<O>>& fields, const OptionValues& values) {
  O o{};
  for (const auto& [key, value] : values) {
    const std::string& name = key;  // clang before 16 cannot capture a structured binding
    auto it = std::find_if(fields.begin(), fields.end(), [&](const Field<O>& f) { return f.info.name == name; });
    if (it == fields.end()) {
      std::string valid;
      for (const Field<O>& f : fields) valid += (valid.empty() ? "" : ", ") + f.info.name;
      fail_input("study " + study + ": unknown option '" + name + "' (options: " + valid + ")");
    }
    it->set(o, value);
  }
  return o;
}

template <typename O>
using RunFn = Results (*)(const Scene&, const O&, const StudyOutput&, Progress*);
template <typename O>
using PartFn = Results (*)(const Scene&, const O&, const FramePart&, const StudyOutput&, FrameFigures&, Progress*);
template <typename O>
using PartResultsFn = Results (*)(const Scene&, const O&, const FrameFigures&);

// `finish`, when given, sets what the command line derives from the flags given; `part` and
// `part_results`, when given, run the study split into frame parts.
template <typename O>
Entry entry(const char* name, const char* summary, std::vector<Field<O>> fields, RunFn<O> run,
            void (*finish)(O&, const OptionValues&) = nullptr, PartFn<O> part = nullptr,
            PartResultsFn<O> part_results = nullptr) {
  auto table = std::make_shared<const std::vector<Field<O>>>(std::move(fields));
  Entry e;
  e.info.name = name;
  e.info.summary = summary;
  for (const Field<O>& f : *table) e.info.options.push_back(f.info);
  auto make = [table, study = std::string(name), finish](const OptionValues& values) {
    O o = apply_options(study, *table, values);
    if (finish) finish(o, values);
    return o;
  };
  e.resolve = [table, make](const OptionValues& values) {
    const O o = make(values);
    OptionValues all;
    for (const Field<O>& f : *table) all[f.info.name] = f.get(o);
    return all;
  };
  e.run = [make, run](const Scene& scene, const OptionValues& values, const StudyOutput& out, Progress* progress) {
    return run(scene, make(values), out, progress);
  };
  if (part && part_results) {
    e.run_part = [make, part](const Scene& scene, const OptionValues& values, const FramePart& p,
                              const StudyOutput& out, FrameFigures& figures, Progress* progress) {
      return part(scene, make(values), p, out, figures, progress);
    };
    e.part_results = [make, part_results](const Scene& scene, const OptionValues& values,
                                          const FrameFigures& figures) {
      return part_results(scene, make(values), figures);
    };
  }
  return e;
}

Entry reference_entry() {
  using O = ReferenceStudyOptions;
  std::vector<Field<O>> f;
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("width", "image width, pixels", &O::width));
  f.push_back(field<O>("height", "image height, pixels", &O::height));
  f.push_back(field<O>("seed", "the sub-sample and light-sample streams", &O::seed));
  f.push_back(field<O>("spp", "k: k×k stratified samples per pixel, 1..64", &O::supersample));
  f.push_back(field<O>("light_samples", "n: n×n samples per area light, 1..64", &O::light_samples));
  f.push_back(field<O>("glossy_rays", "rays per glossy lobe, 1..4096", &O::glossy_rays));
  f.push_back(field<O>("bounces", "reflection depth, 0..16 (0 = no reflections)", &O::bounces));
  f.push_back(field<O>("time", "seconds: pose of animated scenes; < 0 = the path frame's time, or 0", &O::time));
  return entry<O>("reference", "the Embree reference render of one camera (proxima render)", std::move(f),
                  run_reference);
}

Entry sampling_entry() {
  using O = SamplingOptions;
  std::vector<Field<O>> f;
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("width", "pixels, of every depth image and output frame", &O::width));
  f.push_back(field<O>("height", "pixels", &O::height));
  f.push_back(field<O>("seed", "of the K intermediate viewpoints", &O::seed));
  f.push_back(field<O>("method", "sampling methods, comma-separated; several share the frames", &O::methods));
  f.push_back(field<O>("views", "view set: segment (2 views), triangle (3), rectangle (4)", &O::views));
  f.push_back(field<O>("redundancy",
                       "the definition every metric uses; empty = visibility when nrr-visibility is the only NRR "
                       "method, else pixel",
                       &O::redundancy));
  f.push_back(field<O>("frames", "K intermediate output frames, 0..100000", &O::frames));
  f.push_back(field<O>("radius", "m, of the views from the centre; 0 = 8 % of the focus distance", &O::radius));
  f.push_back(field<O>("reps", "timed repetitions of each method (median), 1..100", &O::reps));
  return entry<O>("sampling", "depth-image sampling: conventional, peeling, NRR (proxima sample)", std::move(f),
                  run_sampling);
}

Entry shadows_entry() {
  using O = ShadowsOptions;
  std::vector<Field<O>> f;
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("sampling", "occluder samplings, comma-separated; several share the ground truths",
                       &O::samplings));
  f.push_back(field<O>("light_size", "light diagonal / scene bounding-box diagonal, (0, 100]", &O::light_size));
  f.push_back(field<O>("light_samples", "n: the light is sampled n × n, 1..64", &O::light_samples));
  f.push_back(field<O>("ref_res", "pixels (square) of the reference depth images", &O::ref_res));
  f.push_back(field<O>("out_res", "pixels (square) of the output image", &O::out_res));
  f.push_back(field<O>("shadow_res", "shadow-map texel density: of a map this side over the light field",
                       &O::shadow_res));
  f.push_back(field<O>("full_maps", "shadow maps cover the whole light field (not fitted to the receivers)",
                       &O::full_maps));
  f.push_back(field<O>("shadow_footprint", "texels per receiver footprint, 0..16 (0: shadow_res alone)",
                       &O::shadow_footprint));
  f.push_back(field<O>("redundancy", "NRR's redundancy test", &O::redundancy));
  f.push_back(field<O>("reconstruction", "hybrid (Algorithm 4) or conventional mesh", &O::reconstruction));
  f.push_back(field<O>("no_rays", "skip the Embree shadow-ray ground truth", &O::no_rays));
  return entry<O>("shadows", "soft shadows through reconstructed depth images (proxima shadows)", std::move(f),
                  run_shadows);
}

Entry envmap_entry() {
  using O = EnvmapReflectOptions;
  std::vector<Field<O>> f;
  f.push_back(field<O>("method", "envmap | rectified | average | layered | boxprobe | reference", &O::method));
  f.push_back(field<O>("compare", "every method and the reference instead of `method`", &O::compare));
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("width", "image width, pixels", &O::width));
  f.push_back(field<O>("height", "image height, pixels", &O::height));
  f.push_back(field<O>("seed", "area-light, lobe and map texel streams", &O::seed));
  f.push_back(field<O>("d_e", "rectification tolerance d_e, meters", &O::d_e));
  f.push_back(field<O>("distance", "search length D, meters; 0 = the scene's bounding-box diagonal", &O::distance));
  f.push_back(field<O>("cube_size", "cube-map face side, texels", &O::cube_size));
  f.push_back(field<O>("angle_step", "sampling step s of the average distance, degrees", &O::angle_step_deg));
  f.push_back(field<O>("edge", "black | fallback (plain lookup) where the search ends beside the map", &O::edge));
  f.push_back(field<O>("light_samples", "n of the n×n samples per area light", &O::light_samples));
  f.push_back(field<O>("glossy_rays", "lobe rays (lookups) per glossy pixel", &O::glossy_rays));
  f.push_back(field<O>("reps", "timed frames per method, round-robin over the methods", &O::reps));
  f.push_back(field<O>("layers", "layered: depth layers peeled from the map's center", &O::layers));
  f.push_back(field<O>("march_steps", "layered: ray-march samples per lookup at most", &O::march_steps));
  f.push_back(field<O>("max_maps", "env maps at most: reflectors grouped, one map per group", &O::max_maps));
  f.push_back(field<O>("group_parallax", "reflectors share a map while its mean parallax is at most this",
                       &O::group_parallax));
  return entry<O>("envmap_reflect", "reflections through environment maps with distance (proxima reflect)",
                  std::move(f), run_envmap_reflect);
}

// The command line's --frame: one frame of the path instead of the whole path.
void cluster_finish(ClusterReflectOptions& o, const OptionValues& values) { o.frame_given = values.contains("frame"); }

Entry cluster_entry() {
  using O = ClusterReflectOptions;
  using R = ReflectionOptions;
  using C = ClusterReflectionOptions;
  std::vector<Field<O>> f;
  f.push_back(field<O>("width", "output pixels", &O::width));
  f.push_back(field<O>("height", "output pixels", &O::height));
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("compare", "Embree on the same rays + env mapping: errors, occlusion errors, timing",
                       &O::compare));
  f.push_back(field<O>("reps", "timing repetitions per frame (medians), 1..100", &O::reps));
  f.push_back(field<O>("cube_size", "env-map comparison: cube face side, texels", &O::cube_size));
  f.push_back(field<O>("d_e", "env-map comparison: rectification tolerance, meters", &O::d_e));
  f.push_back(field<O>("distance", "env-map comparison: search length D, meters; 0 = the scene's diagonal",
                       &O::distance));
  f.push_back(field<O>("edge_fallback", "env-map comparison: plain lookup where the search ends beside the map",
                       &O::edge_fallback));
  f.push_back(field<O>("max_maps", "env-map comparison: maps at most, one per group of reflectors",
                       &O::envmap_groups, &EnvmapGroupOptions::max_groups));
  f.push_back(field<O>("group_parallax", "env-map comparison: reflectors share a map while its parallax is at most this",
                       &O::envmap_groups, &EnvmapGroupOptions::max_parallax));
  f.push_back(field<O>("frames", "frames the path is divided into; 0 = the path's own count", &O::frames));
  f.push_back(field<O>("frame_step", "run every frame_step-th frame", &O::frame_step));
  f.push_back(field<O>("image_frame", "frame whose images are written; -1 = the first one rendered", &O::image_frame));
  f.push_back(field<O>("full_reference", "also render_reference (shadows, jittered area light, 1 bounce)",
                       &O::full_reference));
  f.push_back(field<O>("ssr", "also screen-space reflections with the box-probe fallback on the same rays",
                       &O::ssr));
  f.push_back(field<O>("ss", "K×K samples per pixel (the reference's sub-pixel grid)", &O::reflection, &R::supersample));
  f.push_back(field<O>("glossy_rays", "lobe rays per glossy sample", &O::reflection, &R::glossy_rays));
  f.push_back(field<O>("light_samples", "n of the n×n area-light samples", &O::reflection, &R::area_light_samples));
  f.push_back(field<O>("seed", "lobe and light sample streams", &O::reflection, &R::seed));
  f.push_back(field<O>("theta_bins", "MAXTHETABINS", &O::cluster, &C::clustering, &ClusteringOptions::max_theta_bins));
  f.push_back(field<O>("phi_bins", "MAXPHIBINS", &O::cluster, &C::clustering, &ClusteringOptions::max_phi_bins));
  f.push_back(field<O>("min_bin_scale", "lower bound of a reflector's bin scale per axis, 0..1", &O::cluster,
                       &C::clustering, &ClusteringOptions::min_bin_scale));
  f.push_back(field<O>("resolution_scale", "cluster image texels per pixel footprint", &O::cluster,
                       &C::resolution_scale));
  f.push_back(field<O>("second_layer", "glossy and curved clusters get a second depth layer", &O::cluster,
                       &C::second_layer));
  f.push_back(field<O>("own_exact",
                       "curved clusters' rays intersected exactly with their own reflector (false = own layer)",
                       &O::cluster, &C::own_exact));
  f.push_back(field<O>("march_block", "block size of the depth minima the march skips with (0 = none; same result)",
                       &O::cluster, &C::march_block));
  f.push_back(field<O>("glossy_march_coarse", "glossy lobe rays march the nearest depth per B×B texels (1 = full image)",
                       &O::cluster, &C::glossy_march_coarse));
  f.push_back(field<O>("lod", "level of detail: largest cell in texel footprints (0 = exact triangles)", &O::cluster,
                       &C::lod_texels));
  return entry<O>("cluster_reflect", "reflections from clustered depth images (proxima reflect --method cluster)",
                  std::move(f), run_cluster_reflect, cluster_finish, run_cluster_reflect_part,
                  cluster_reflect_results);
}

Entry temporal_entry() {
  using O = TemporalReflectOptions;
  std::vector<Field<O>> f;
  f.push_back(field<O>("width", "output pixels", &O::width));
  f.push_back(field<O>("height", "output pixels", &O::height));
  f.push_back(field<O>("path", "camera path, index or name (required)", &O::path));
  f.push_back(field<O>("compare", "also full ray tracing and direct reprojection, errors and speed-up", &O::compare));
  f.push_back(field<O>("light_samples", "n of the n×n area-light stratum centres, 1..64", &O::light_samples));
  f.push_back(field<O>("glossy_rays", "lobe rays per glossy sample, 1..1024", &O::glossy_rays));
  f.push_back(field<O>("seed", "lobe and light sample streams", &O::seed));
  f.push_back(field<O>("frames", "frames the path is divided into; 0 = the path's own count", &O::frames));
  f.push_back(field<O>("frame_step", "render every frame_step-th frame (reuse spans the skipped ones)",
                       &O::frame_step));
  f.push_back(field<O>("threshold", "key-frame threshold on the recomputed fraction, [0, 1]", &O::threshold));
  f.push_back(field<O>("stretch_limit", "warp triangles stretched more than this (area ratio) are unreliable",
                       &O::stretch_limit));
  f.push_back(field<O>("spread_limit", "curved reflectors' spread limit; inf = off", &O::spread_limit));
  f.push_back(field<O>("depth_discontinuity", "warp corners differing by more than this fraction are not connected",
                       &O::depth_discontinuity));
  f.push_back(field<O>("curved_contrast", "the spread limit applies only above this contrast (linear)",
                       &O::curved_contrast));
  f.push_back(field<O>("edge_contrast", "warp triangles above this contrast follow edge_rule; inf = off",
                       &O::edge_contrast));
  f.push_back(field<O>("edge_rule", "on such an edge: nearest corner's Lr, or recompute", &O::edge_rule));
  f.push_back(field<O>("recompute_splats", "samples no warp triangle reached are recomputed", &O::recompute_splats));
  f.push_back(field<O>("blend_error", "reused samples above this expected display error are recomputed; inf = off",
                       &O::blend_error));
  f.push_back(field<O>("refine_error", "reused neighbours of samples seen to err above this are recomputed; inf = off",
                       &O::refine_error));
  f.push_back(field<O>("learn_error", "key pixels where reuse was seen to err above this are recomputed; inf = off",
                       &O::learn_error));
  f.push_back(field<O>("keyframe_cost", "rays per reflective key pixel the fixed steps cost; 0 = off",
                       &O::keyframe_cost));
  f.push_back(field<O>("match_extrapolate", "best match also starts from the last change continued",
                       &O::match_extrapolate));
  f.push_back(field<O>("image_frame", "frame whose images are written; -1 = the first non-key frame",
                       &O::image_frame));
  f.push_back(field<O>("lobe_seed_cell", "> 0 seeds lobe rays per world cell of this edge × the diagonal",
                       &O::lobe_seed_cell));
  f.push_back(field<O>("breakdown", "with compare: error by pixel class, key-frame age, seed noise", &O::breakdown));
  f.push_back(field<O>("reference_rays", "with compare: > 0 also errors against a reference with this many lobe rays",
                       &O::reference_rays));
  return entry<O>("temporal_reflect", "temporal reuse of reflections (proxima reflect --method temporal)",
                  std::move(f), run_temporal_reflect);
}

Entry visibility_entry() {
  using O = VisibilityOptions;
  std::vector<Field<O>> f;
  f.push_back(field<O>("width", "map width, pixels", &O::width));
  f.push_back(field<O>("height", "map height, pixels", &O::height));
  f.push_back(field<O>("path", "camera path by index or name; empty = the first", &O::path));
  f.push_back(field<O>("frames", "viewpoints = the path's first N frames; 0 = every frame", &O::frames));
  f.push_back(field<O>("oracle", "compare every map with Embree's item buffer (--no-oracle clears it)", &O::oracle));
  f.push_back(field<O>("images", "map_NNN.svg and map_NNN.png per viewpoint (--no-images clears it)", &O::images));
  f.push_back(field<O>("selfcheck_rays", "Embree rays per map's self-check, 1..1000000", &O::selfcheck_rays));
  f.push_back(field<O>("load", "winged-pair file traced instead of building one; empty = build", &O::load));
  f.push_back(field<O>("save", "file the winged pair is written to; empty = none", &O::save));
  return entry<O>("visibility", "exact visibility maps along a camera path (proxima visibility)", std::move(f),
                  run_visibility, nullptr, run_visibility_part, visibility_results);
}

std::vector<Field<GibrOptions>> gibr_fields() {
  using O = GibrOptions;
  using M = gibr::GibrModelOptions;
  std::vector<Field<O>> f;
  f.push_back(field<O>("width", "novel views and their ground truth, pixels", &O::width));
  f.push_back(field<O>("height", "novel views and their ground truth, pixels", &O::height));
  f.push_back(field<O>("seed", "photograph poses, textures, photograph and ground-truth samples", &O::seed));
  f.push_back(field<O>("photos", "calibrated photographs rendered along the walk path", &O::model, &M::photos));
  f.push_back(field<O>("photo_width", "photograph width, pixels", &O::model, &M::photo_width));
  f.push_back(field<O>("photo_height", "photograph height, pixels", &O::model, &M::photo_height));
  f.push_back(field<O>("camera_file", "photographs from this camera file instead of rendered ones", &O::model,
                       &M::camera_file));
  f.push_back(field<O>("texel", "radiance-map texel, meters; 0 = per scene", &O::model, &M::texel));
  f.push_back(field<O>("period", "texture repeat, meters; 0 = per scene", &O::model, &M::period));
  f.push_back(field<O>("supersample", "k×k samples per photograph / ground-truth pixel", &O::model, &M::supersample));
  f.push_back(field<O>("exclude_boundaries", "vismap mapping also drops pixels touching polygon edges", &O::model,
                       &M::exclude_boundaries));
  f.push_back(field<O>("whole_pixels", "vismap mapping without exact-visible texels", &O::model, &M::whole_pixels));
  f.push_back(field<O>("unmix", "unmix silhouette pixels (--no-unmix clears it)", &O::model, &M::unmix));
  f.push_back(field<O>("unmix_two_pass", "unmix thin occluders' pixels from the first pass's colors", &O::model,
                       &M::unmix_two_pass));
  f.push_back(field<O>("photo_yaw", "photographs' view directions turned by up to ± this, degrees, 0..180", &O::model,
                       &M::photo_yaw_deg));
  f.push_back(field<O>("photo_backoff", "meters the photographs step back, 0..1000", &O::model, &M::photo_backoff));
  f.push_back(field<O>("calibration_px", "mapping cameras turned by this many pixels, 0..100", &O::model,
                       &M::calibration_px));
  f.push_back(field<O>("views", "novel views: path, offpath or photos", &O::views));
  f.push_back(field<O>("frames", "novel views rendered and compared, 1..10000", &O::frames));
  f.push_back(field<O>("k", "photographs blended per pixel, 1..64", &O::k));
  f.push_back(field<O>("novel_ss", "s×s samples per novel-view pixel, 0..8; 0 = supersample", &O::novel_ss));
  f.push_back(field<O>("hole_radius", "texels searched around a hole, 0..4096", &O::hole_radius));
  f.push_back(field<O>("mixed_reach", "holes take a kMixed sample within this many texels first, 0..64",
                       &O::mixed_reach));
  f.push_back(field<O>("offpath", "meters the offpath views move off the path, 0..1000", &O::offpath));
  f.push_back(field<O>("photo_images", "photos/photo_NNN.png (--no-photo-images clears it)", &O::photo_images));
  f.push_back(field<O>("fps_repeat", "timed renders per novel view (median), 1..1000", &O::fps_repeat));
  return f;
}

Entry gibr_entry() {
  return entry<GibrOptions>("gibr", "hybrid geometry- and image-based rendering (proxima gibr)", gibr_fields(),
                            run_gibr);
}

Entry trace_bench_entry() {
  using O = TraceBenchOptions;
  std::vector<Field<O>> f;
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("width", "pixels: one primary ray per pixel", &O::width));
  f.push_back(field<O>("height", "pixels", &O::height));
  f.push_back(field<O>("threads", "the \"all threads\" count (<= 0 = all cores); 1 is timed too", &O::threads));
  f.push_back(field<O>("reps", "repetitions per measurement, 1..1000 (median)", &O::reps));
  return entry<O>("trace_bench", "Embree's BVH build and rays per second (proxima bench trace)", std::move(f),
                  run_trace_bench);
}

Entry raster_bench_entry() {
  using O = RasterBenchStudyOptions;
  std::vector<Field<O>> f;
  add_camera_fields(f, &O::camera);
  f.push_back(field<O>("width", "pixels", &O::width));
  f.push_back(field<O>("height", "pixels", &O::height));
  f.push_back(field<O>("threads", "the \"all threads\" count (<= 0 = all cores); 1 is timed too", &O::threads));
  f.push_back(field<O>("reps", "timed frames per measurement, 1..1000 (median)", &O::reps));
  f.push_back(field<O>("skip_agreement", "time only", &O::skip_agreement));
  return entry<O>("raster_bench", "the rasterizer against Embree (proxima bench raster)", std::move(f),
                  run_raster_bench);
}

Entry technique_bench_entry() {
  using O = TechniqueBenchOptions;
  std::vector<Field<O>> f;
  f.push_back(field<O>("techniques", "comma-separated techniques, or all", &O::techniques));
  f.push_back(field<O>("reps", "interleaved repetitions, 1..100 (medians)", &O::reps));
  f.push_back(field<O>("sweep", "also the other settings of each technique's knob", &O::sweep));
  f.push_back(field<O>("seed", "the studies' sample streams", &O::seed));
  return entry<O>("technique_bench", "every technique beside Embree (proxima bench techniques)", std::move(f),
                  run_technique_bench);
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> all = [] {
    std::vector<Entry> e{cluster_entry(),  envmap_entry(),      gibr_entry(),     raster_bench_entry(),
                         reference_entry(), sampling_entry(),   shadows_entry(),  temporal_entry(),
                         technique_bench_entry(), trace_bench_entry(), visibility_entry()};
    std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) { return a.info.name < b.info.name; });
    return e;
  }();
  return all;
}

const Entry& find_entry(std::string_view name) {
  for (const Entry& e : entries())
    if (e.info.name == name) return e;
  std::string valid;
  for (const Entry& e : entries()) valid += (valid.empty() ? "" : ", ") + e.info.name;
  fail_input("unknown study '" + std::string(name) + "' (studies: " + valid + ")");
}

}  // namespace

const std::vector<StudyInfo>& study_catalog() {
  static const std::vector<StudyInfo> infos = [] {
    std::vector<StudyInfo> v;
    for (const Entry& e : entries()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

const StudyInfo& study_info(std::string_view name) { return find_entry(name).info; }

OptionValues resolved_options(std::string_view name, const OptionValues& options) {
  return find_entry(name).resolve(options);
}

Results run_study(std::string_view name, const Scene& scene, const OptionValues& options, const StudyOutput& out,
                  Progress* progress) {
  return find_entry(name).run(scene, options, out, progress);
}

bool splits_by_frames(std::string_view name) { return bool(find_entry(name).run_part); }

Results run_study_part(std::string_view name, const Scene& scene, const OptionValues& options, const FramePart& part,
                       const StudyOutput& out, FrameFigures& figures, Progress* progress) {
  const Entry& e = find_entry(name);
  if (!e.run_part) fail_input("study " + std::string(name) + " does not split into frame parts");
  return e.run_part(scene, options, part, out, figures, progress);
}

Results study_part_results(std::string_view name, const Scene& scene, const OptionValues& options,
                           const FrameFigures& figures) {
  const Entry& e = find_entry(name);
  if (!e.part_results) fail_input("study " + std::string(name) + " does not split into frame parts");
  return e.part_results(scene, options, figures);
}

GibrOptions gibr_options(const OptionValues& options) { return apply_options("gibr", gibr_fields(), options); }

namespace {

// The value of a command's --method, or "".
std::string command_method(const std::vector<std::string>& a) {
  for (size_t i = 1; i + 1 < a.size(); ++i)
    if (a[i] == "--method") return a[i + 1];
  return "";
}

// The catalog study of a command and the arguments after the command's name.
std::pair<std::string, size_t> command_study(const std::vector<std::string>& a) {
  if (a.empty()) fail_input("an empty command");
  if (a[0] == "reflect") {
    const std::string m = command_method(a);
    // --method ssr is the cluster study with screen-space reflections beside it
    const bool cluster = m == "cluster" || m == "ssr";
    return {m == "temporal" ? "temporal_reflect" : cluster ? "cluster_reflect" : "envmap_reflect", 1};
  }
  if (a[0] == "bench" && a.size() > 1 && (a[1] == "raster" || a[1] == "trace")) return {a[1] + "_bench", 2};
  static const std::map<std::string, std::string> kCommands{
      {"render", "reference"}, {"sample", "sampling"},     {"shadows", "shadows"},
      {"visibility", "visibility"}, {"gibr", "gibr"}};
  const auto it = kCommands.find(a[0]);
  if (it == kCommands.end()) fail_input("'" + a[0] + "': not a command that runs a study");
  return {it->second, 1};
}

// The value of option `info` as the text `text` gives it.
OptionValue parse_option(const OptionInfo& info, const std::string& text, const std::string& flag) {
  try {
    size_t used = 0;
    if (info.type == "int") {
      const std::int64_t v = std::stoll(text, &used);
      if (used == text.size()) return v;
    } else if (info.type == "float") {
      if (text == "inf" || text == "-inf") return text;
      const double v = std::stod(text, &used);
      if (used == text.size()) return v;
    } else {
      return text;
    }
  } catch (const std::exception&) {
  }
  fail_input(flag + ": '" + text + "' is not " + (info.type == "int" ? "an integer" : "a number"));
}

const OptionInfo* find_option(const StudyInfo& study, const std::string& name) {
  for (const OptionInfo& o : study.options)
    if (o.name == name) return &o;
  return nullptr;
}

}  // namespace

CatalogRun catalog_run_from_command(const std::vector<std::string>& a) {
  const auto [name, first] = command_study(a);
  const StudyInfo& study = study_info(name);
  CatalogRun run{name, "", {}};
  std::string floors;
  for (size_t i = first; i < a.size(); ++i) {
    const std::string& flag = a[i];
    if (flag.size() < 3 || flag.compare(0, 2, "--") != 0) fail_input("'" + flag + "': expected a --flag");
    std::string key = flag.substr(2);
    std::replace(key.begin(), key.end(), '-', '_');
    if (key == "gloss_rays") key = "glossy_rays";
    const OptionInfo* info = find_option(study, key);
    // Flags that choose the scene, the study (reflect --method temporal) or the output.
    const bool command_flag = key == "scene" || key == "floors" || key == "out" || (key == "threads" && !info) ||
                              (key == "method" && a[0] == "reflect" && name != "envmap_reflect");
    if (!command_flag && !info) {
      const OptionInfo* cleared = key.rfind("no_", 0) == 0 ? find_option(study, key.substr(3)) : nullptr;
      if (!cleared || cleared->type != "bool") fail_input(flag + ": not an option of study " + name);
      run.options[cleared->name] = false;
      continue;
    }
    if (info && info->type == "bool") {
      run.options[key] = true;
      continue;
    }
    if (i + 1 >= a.size()) fail_input(flag + ": needs a value");
    const std::string& value = a[++i];
    if (key == "scene") run.scene = value;
    else if (key == "floors") floors = value;
    else if (!command_flag) run.options[key] = parse_option(*info, value, flag);
  }
  if (!floors.empty()) run.scene += ":floors=" + floors;
  if (name == "cluster_reflect" && command_method(a) == "ssr") run.options["ssr"] = true;
  if (name == "sampling" && !run.options.count("height") && run.options.count("width"))
    run.options["height"] = run.options["width"];
  return run;
}

std::string option_text(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) {
    if (std::isinf(*d)) return *d > 0 ? "inf" : "-inf";
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, *d);  // shortest text that reads back the same
    return std::string(buf, end);
  }
  return std::get<std::string>(value);
}

}  // namespace proxima::study
