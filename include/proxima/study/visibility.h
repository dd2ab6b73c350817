// The exact-visibility study (`proxima visibility`, docs/visibility.md): Funkhouser's
// visibility maps (BSP → winged pair → beam tracing) along a scene's camera path — the
// build statistics in the paper's Table 1 shape, per-viewpoint statistics in its Table 2
// shape, agreement with Embree's item buffer at every pixel center (visibility/oracle.h) and
// the self-check of every map (visibility/map_check.h), with an SVG and a PNG of every map.
#pragma once

#include <string>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/scene.h"
#include "proxima/study/frame_split.h"
#include "proxima/study/study.h"
#include "proxima/visibility/map_check.h"

namespace proxima::study {

struct VisibilityOptions {
  int width = 1024, height = 1024;  // --width, --height: map size in pixels (≤ kMaxImageSide)
  std::string path;                 // --path: camera path by index or name; empty = the first
  int frames = 0;                   // --frames: viewpoints = the path's first N frames; 0 = every frame
  bool oracle = true;               // --no-oracle clears it: compare every map with Embree's item buffer
  bool images = true;               // --no-images clears it: map_NNN.svg and map_NNN.png per viewpoint
  int selfcheck_rays = visibility::MapCheckOptions{}.rays;  // --selfcheck-rays: Embree rays per map's self-check
  std::string load;                 // --load: winged-pair file traced instead of building one; empty = build
  std::string save;                 // --save: file the winged pair is written to; empty = none
};

// Throws InputError naming the flag: --frames < 0, --selfcheck-rays outside 1..1000000,
// --width/--height not a valid image size (core/camera.h validate_camera).
void validate(const VisibilityOptions& options);

// Traces a visibility map at each of the first `frames` frames of the chosen camera path
// (near 1e-3, far scene_far_plane), checks each and (oracle) compares each with Embree.
// Metrics (all counts are sums or averages over the viewpoints): polygons, cells, faces,
// edges, vertices, build_ms, unplaced_fragments, rejected_planes, viewpoints, map_ms_avg/max,
// beams_avg/max, maps_failed_selfcheck, selfcheck_ms_avg/max, selfcheck_samples,
// selfcheck_mismatches, selfcheck_coplanar_ties, regions_avg, merged_regions_avg,
// visible_polygons_avg, silhouette_edges_avg; with the oracle agreement_pct,
// agreement_interior_pct, agreement_with_ties_pct, agreement_interior_with_ties_pct, each
// also as _worst (the lowest viewpoint), occluded_label_samples, oracle_samples. Tables: the
// winged pair (Table 1), beam tracing (Table 2), one row per viewpoint. Images (images and
// out.writes()): map_NNN.svg / .png per frame, roles map_svg and map_png for frame 0.
// A map failing its self-check is warned about on stderr (frame, eye, reason) and counted
// in maps_failed_selfcheck; the run goes on.
// Inputs are read before anything is written: a scene without a camera path (naming
// --scene), an unknown path (--path), a --load file that cannot be read or was built for
// another polygon count (naming --load and the file) throw InputError; so does a loaded
// winged pair that cannot be traced (naming the file; earlier frames' maps stay written).
// Deterministic: the same results (timings aside) at any thread count.
Results run_visibility(const Scene& scene, const VisibilityOptions& options, const StudyOutput& out,
                       Progress* progress = nullptr);

// The run split into frame parts (study/frame_split.h) over its viewpoints: one part's
// maps, their figures into `figures` (part 0's also the winged pair's, and part 0 alone
// saves it) and their images into `out` (the roles map_svg / map_png by the part with
// frame 0); and the whole run's metrics and tables (no images) from every part's figures
// concatenated in part order — run_visibility's, bit for bit (timings aside). Every part
// with frames builds (or loads) the winged pair itself.
Results run_visibility_part(const Scene& scene, const VisibilityOptions& options, const FramePart& part,
                            const StudyOutput& out, FrameFigures& figures, Progress* progress = nullptr);
Results visibility_results(const Scene& scene, const VisibilityOptions& options, const FrameFigures& figures);

}  // namespace proxima::study
