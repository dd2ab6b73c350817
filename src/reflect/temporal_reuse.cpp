// Temporal reuse of reflections (thesis ch. 5, Algorithm 8 and §5.4.4 key-frame policy).
#include "proxima/reflect/temporal_reuse.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "proxima/core/timer.h"

namespace proxima {

namespace {

// Reflection rays that escape store s.r = this × the scene diagonal: far enough that R
// behaves like a direction in the match distance, finite for the warp's depth test.
constexpr float kEscapeDistanceScale = 100.0f;

// Traces the samples listed in `todo` into `radiance`; returns how many rays it traced.
uint64_t trace_listed(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                      const std::vector<uint32_t>& todo, std::vector<vec3>& radiance) {
  uint64_t traced_rays = 0;
  for (uint32_t i : todo) traced_rays += frame.first_ray[i + 1] - frame.first_ray[i];
  trace_reflection_samples(scene, rays, frame, todo, radiance);
  return traced_rays;
}

// Traces the flagged samples into r.radiance (listed in `todo`, reused); returns how many
// rays it traced. `observed` (may be null) receives the kReuseKept samples with their
// reuse values.
uint64_t recompute(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame, ReflectionReprojection& r,
                   std::vector<uint32_t>& todo, std::vector<std::pair<uint32_t, vec3>>* observed = nullptr) {
  todo.clear();
  if (observed) observed->clear();
  for (size_t i = 0; i < r.flag.size(); ++i)
    if (r.flag[i] != kReuseOk) {
      todo.push_back(uint32_t(i));
      if (observed && (r.flag[i] & kReuseKept)) observed->emplace_back(uint32_t(i), r.radiance[i]);
    }
  return trace_listed(scene, rays, frame, todo, r.radiance);
}

// The display error (0–255, any channel) of the reuse value `reused` of sample i where the
// trace gave `traced`: the blend risk of one sample of weight 1.
float observed_error(const ReflectionFrame& frame, size_t i, vec3 reused, vec3 traced) {
  const float* rgb = frame.base.data().data() + size_t(frame.pixel[i]) * 3u;
  BlendSamples truth;
  truth.lr[0] = traced, truth.w[0] = 1.0f, truth.n = 1;
  return blend_risk(truth, reused, frame.specular[i], vec3(rgb[0], rgb[1], rgb[2]));
}

// learn_error, before the recompute: reused samples projecting into a key pixel marked on an
// earlier frame of this key cycle are recomputed, their reuse value kept to be observed.
void flag_marked(const std::vector<uint8_t>& marked, ReflectionReprojection& r, TemporalFrameStats& st) {
  uint64_t added = 0;
  for (size_t i = 0; i < r.flag.size(); ++i)
    if (r.flag[i] == kReuseOk && r.key_pixel[i] != kNoKeyPixel && marked[r.key_pixel[i]]) {
      r.flag[i] = uint8_t(kReuseUnreliable | kReuseLearned | kReuseKept);
      ++added;
    }
  r.unreliable += added;
  st.learned += added;
}

// After the recompute: each observed error above learn_error marks its key pixel, above
// refine_error its reused 8-neighbours on the same reflector are traced (and observed) next
// round. Serial over the observations in a fixed order, so the same samples for any thread
// count; each round's additions are traced together. Returns the rays traced.
uint64_t feed_back(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame, ReflectionReprojection& r,
                   TemporalState& state, const TemporalOptions& options, TemporalFrameStats& st) {
  constexpr uint32_t kNone = 0xFFFFFFFFu;
  const int w = frame.sample_camera.width, h = frame.sample_camera.height;
  const bool refining = options.refine_error < kInf;
  std::vector<uint32_t>& sample_at = state.sample_at;
  if (refining) {
    sample_at.assign(size_t(w) * size_t(h), kNone);
    for (size_t i = 0; i < frame.pixel.size(); ++i) sample_at[frame.pixel[i]] = uint32_t(i);
  }
  uint64_t traced_rays = 0, added = 0;
  std::vector<std::pair<uint32_t, vec3>>& observed = state.observed;
  std::vector<std::pair<uint32_t, vec3>>& next = state.next;
  while (!observed.empty()) {
    st.observed += observed.size();
    next.clear();
    for (const auto& [i, reused] : observed) {
      const float error = observed_error(frame, i, reused, r.radiance[i]);
      if (error > options.learn_error && r.key_pixel[i] != kNoKeyPixel) state.marked[r.key_pixel[i]] = 1;
      if (!(error > options.refine_error)) continue;
      const int x = int(frame.pixel[i] % uint32_t(w)), y = int(frame.pixel[i] / uint32_t(w));
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const uint32_t j = sample_at[size_t(ny) * size_t(w) + size_t(nx)];
          if (j == kNone || r.flag[j] != kReuseOk || frame.reflector[j] != frame.reflector[i]) continue;
          r.flag[j] = uint8_t(kReuseUnreliable | kReuseRefined | kReuseKept);
          next.emplace_back(j, r.radiance[j]);
        }
    }
    if (next.empty()) break;
    state.todo.clear();
    for (const auto& [j, reused] : next) state.todo.push_back(j);
    traced_rays += trace_listed(scene, rays, frame, state.todo, r.radiance);
    added += next.size();
    ++st.refine_rounds;
    std::swap(observed, next);
  }
  r.unreliable += added;
  st.refined += added;
  return traced_rays;
}

}  // namespace

std::vector<vec3> temporal_reflections(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                                       TemporalState& state, const TemporalOptions& options,
                                       TemporalFrameStats* stats, std::vector<uint8_t>* flags) {
  std::vector<vec3> radiance;
  temporal_reflections_into(scene, rays, frame, state, options, radiance, stats, flags);
  return radiance;
}

void temporal_reflections_into(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                               TemporalState& state, const TemporalOptions& options, std::vector<vec3>& radiance,
                               TemporalFrameStats* stats, std::vector<uint8_t>* flags) {
  if (frame.supersample != 1) throw std::logic_error("temporal reflections: frame must have supersample 1");
  TemporalFrameStats st;
  st.reflective = frame.sample_count();
  st.rays = frame.direction.size();
  const bool size_changed =
      state.key.camera.width != frame.camera.width || state.key.camera.height != frame.camera.height;
  if (state.need_key || size_changed) {
    // Key frame: trace everything, keep the reflection depth image.
    Stopwatch watch;
    TracedReflections& traced = state.traced;
    trace_reflections_into(scene, rays, frame, traced);
    make_reflection_depth_image_into(frame, traced, kEscapeDistanceScale * frame.scene_diagonal, state.key);
    state.warm_frames = 0;
    state.need_key = false;
    state.frames_since_key = 0;
    state.cycle_work = 1.0;
    st.key = true;
    st.traced_rays = st.rays;
    st.work = 1.0;
    st.key_ms = watch.elapsed_ms();
    radiance.swap(traced.radiance);  // the caller's old buffer is the next key frame's
    if (flags) flags->assign(frame.sample_count(), kReuseOk);
  } else {
    Stopwatch watch;
    BestMatchStats ms;
    OffsetBuffer offsets = std::move(state.spare);
    best_match_search_into(state.key, frame.camera.position, state.warm_frames >= 1 ? &state.previous : nullptr,
                           options.match, offsets, &ms, state.warm_frames >= 2 ? &state.earlier : nullptr);
    st.match_ms = watch.elapsed_ms();
    st.invalid_offsets = ms.invalid;
    st.match_steps = ms.steps;
    watch.restart();
    warp_reflections_into(state.key, offsets, options.warp, state.warp);
    const IntermediateReflection& mid = state.warp;
    st.warp_ms = watch.elapsed_ms();
    watch.restart();
    const WarpedMesh mesh{&state.key, &offsets, &mid, options.warp.edge_contrast, options.warp.edge_rule,
                          options.warp.recompute_splats, options.warp.blend_error};
    ReflectionReprojection& r = state.reprojection;
    reproject_reflections_into(frame, state.key, mid.radiance, &mid.state, options.reproject, &mesh, r);
    st.reproject_ms = watch.elapsed_ms();
    st.disoccluded = r.disoccluded;
    st.unreliable = r.unreliable;
    st.curved = r.curved;
    st.edge = r.edge;
    watch.restart();
    const bool feedback = options.refine_error < kInf || options.learn_error < kInf;
    if (options.learn_error < kInf) {
      const size_t key_size = size_t(state.key.object.width()) * size_t(state.key.object.height());
      if (state.marked_serial != state.key.serial || state.marked.size() != key_size)
        state.marked.assign(key_size, 0), state.marked_serial = state.key.serial;
      flag_marked(state.marked, r, st);
    }
    st.traced_rays = recompute(scene, rays, frame, r, state.todo, feedback ? &state.observed : nullptr);
    if (feedback) st.traced_rays += feed_back(scene, rays, frame, r, state, options, st);
    st.unreliable = r.unreliable;
    st.recomputed = r.recompute();
    st.recompute_ms = watch.elapsed_ms();
    if (options.match.extrapolate) std::swap(state.earlier, state.previous);
    state.spare = std::move(state.previous);  // the oldest: the next frame writes over it
    state.previous = std::move(offsets);
    state.warm_frames = std::min(state.warm_frames + 1, 2);
    ++state.frames_since_key;
    // §5.4.4: too much recomputed → the next frame refreshes the key frame.
    state.need_key = st.stale_fraction() > double(options.keyframe_threshold);
    // The cost rule: the next reuse frame is likely to cost about this one's work; once that
    // reaches the cycle's average, ending the cycle lowers the long-run work per frame.
    if (st.rays > 0)
      st.work = (double(st.traced_rays) + double(options.keyframe_cost) * double(state.key.pixels.size())) /
                double(st.rays);
    state.cycle_work += st.work;
    if (options.keyframe_cost > 0.0f && st.work >= state.cycle_work / double(state.frames_since_key + 1))
      state.need_key = true;
    radiance.swap(r.radiance);  // buffers circulate between the caller and the state
    if (flags) flags->swap(r.flag);
  }
  if (stats) *stats = st;
}

std::vector<vec3> direct_reprojection(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                                      const ReflectionDepthImage& key, const ReprojectOptions& options,
                                      uint64_t* recomputed) {
  ReflectionReprojection r = reproject_reflections(frame, key, key.radiance, nullptr, options);
  if (recomputed) *recomputed = r.recompute();
  std::vector<uint32_t> todo;
  recompute(scene, rays, frame, r, todo);
  return std::move(r.radiance);
}

}  // namespace proxima
