#!/bin/sh
# Cluster reflections against Embree on the same rays, both sides in one run: per frame
# `--reps` interleaved repetitions (G-buffer, Embree BVH build + trace, cluster method),
# medians per frame, then the mean over the frames. Prints wall-clock and process-CPU
# figures, the ratios, the errors and the load average before and after.
#
#   scripts/cluster-bench.sh [PROXIMA] [OUT_DIR]
# Environment: SIZE (512), REPS (5), THREADS (2), STEP (300: frames 0, 300, 600 of 900),
# SCENES ("living-room bathroom"), EXTRA (more `proxima reflect` flags, e.g. "--lod 2").
set -eu
PROXIMA=${1:-build/release/proxima}
OUT=${2:-out/cluster-bench}
SIZE=${SIZE:-512}
REPS=${REPS:-5}
THREADS=${THREADS:-2}
STEP=${STEP:-300}
SCENES=${SCENES:-"living-room bathroom"}
EXTRA=${EXTRA:-}
mkdir -p "$OUT"
for scene in $SCENES; do
  echo "load before $scene: $(cut -d' ' -f1-3 /proc/loadavg)"
  "$PROXIMA" reflect --method cluster --scene "$scene" --path walk --frames 900 --frame-step "$STEP" \
    --width "$SIZE" --height "$SIZE" --ss 2 --gloss-rays 8 --compare --reps "$REPS" --threads "$THREADS" $EXTRA \
    --out "$OUT/$scene" >"$OUT/$scene.md" 2>/dev/null
  echo "load after $scene: $(cut -d' ' -f1-3 /proc/loadavg)"
  /usr/bin/python3 - "$OUT/$scene/results.json" "$scene" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))["metrics"]
g = lambda k: m.get(k, float("nan"))
print(f"{sys.argv[2]}: {int(g('frames'))} frames, {g('clusters_avg'):.1f} clusters, "
      f"{g('triangles_drawn_avg'):.0f} triangles drawn, {g('texels_avg'):.0f} texels avg")
print(f"  wall ms: cluster {g('cluster_ms_avg'):.1f} (G-buffer+clustering {g('gbuffer_clustering_ms_avg'):.1f}, "
      f"cameras {g('cluster_cameras_ms_avg'):.1f}, depth images {g('depth_images_ms_avg'):.1f} "
      f"[shading {g('texel_shading_ms_avg'):.1f}], intersection {g('intersection_ms_avg'):.1f}); "
      f"Embree static {g('reference_ms_avg'):.1f}, with BVH build {g('reference_dynamic_ms_avg'):.1f}; "
      f"speed-up {g('speedup_static'):.2f} static, {g('speedup_dynamic'):.2f} dynamic")
print(f"  cpu ms:  cluster {g('cluster_cpu_ms_avg'):.1f} (G-buffer+clustering {g('gbuffer_clustering_cpu_ms_avg'):.1f}, "
      f"cameras {g('cluster_cameras_cpu_ms_avg'):.1f}, depth images {g('depth_images_cpu_ms_avg'):.1f}, "
      f"intersection {g('intersection_cpu_ms_avg'):.1f}); Embree static {g('reference_cpu_ms_avg'):.1f}, "
      f"with BVH build {g('reference_dynamic_cpu_ms_avg'):.1f}; speed-up {g('speedup_static_cpu'):.2f} static, "
      f"{g('speedup_dynamic_cpu'):.2f} dynamic")
print(f"  errors: mae {g('cluster_mae_r'):.3f} / {g('cluster_mae_g'):.3f} / {g('cluster_mae_b'):.3f}, "
      f"occlusion {g('occlusion_error_pct_avg'):.3f} % avg, {g('occlusion_error_pct_max'):.3f} % max")
PY
done
