#!/bin/sh
# Soft shadows from depth images against Embree shadow rays, both in one run (interleaved
# repetitions, medians; bench/shadows_crossover_bench.cpp): city and grass from 50k to 10M
# triangles at the demo's settings. Prints one row per scene with the depth-image method's
# steps, step 3 as it was (whole-field maps), the Embree BVH build and rays, the ratios
# (> 1: the depth-image method is faster), visibility errors against the rays (0–255),
# peak memory, and the load average before and after.
#
#   scripts/shadows-bench.sh [PROXIMA_BENCH] [OUT_JSON]
# Environment: FILTER (a regex over the benchmark names, default all sizes).
set -eu
BENCH=${1:-build/release/proxima_bench}
OUT=${2:-out/shadows-bench.json}
FILTER=${FILTER:-SoftShadowsVsRays}
mkdir -p "$(dirname "$OUT")"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$BENCH" --benchmark_filter="$FILTER" --benchmark_format=json --benchmark_out="$OUT" >/dev/null
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["benchmarks"]
print("| scene | triangles | occluder tris | step 1 ms | step 2 ms | step 3 ms | step 3 today ms | step 3 speed-up "
      "| depth-image total ms | Embree BVH ms | Embree rays ms | ratio static | ratio with BVH | vis err depth-image "
      "| vis err step 3 today | max RSS MB |")
print("|" + " --- |" * 16)
for b in rows:
    g = lambda k: b.get(k, float("nan"))
    blades = int(b["name"].split("blades:")[1].split("/")[0])
    scene = "city" if blades == 0 else f"grass {blades} blades"
    print(f"| {scene} | {g('triangles'):,.0f} | {g('occluder_triangles'):,.0f} | {g('reference_ms'):.0f} "
          f"| {g('reconstruct_ms'):.0f} | {g('shadow_ms'):.0f} | {g('shadow_today_ms'):.0f} | {g('shadow_speedup'):.2f}x "
          f"| {g('depth_image_ms'):.0f} | {g('bvh_ms'):.0f} | {g('rays_ms'):.0f} | {g('ratio_static'):.2f} "
          f"| {g('ratio_dynamic'):.2f} | {g('vis_error_rays'):.2f} | {g('vis_error_rays_today'):.2f} "
          f"| {g('max_rss_mb'):.0f} |")
PY
