#!/bin/sh
# Soft shadows from depth images against Embree shadow rays, both in one run (interleaved
# repetitions, medians; bench/shadows_crossover_bench.cpp): city and grass from 50k to 10M
# triangles at the demo's settings. Prints per scene the depth-image method's steps, step 3
# as it was (whole-field maps of the unmerged reconstruction), the Embree BVH build and
# rays, the ratios (> 1: the depth-image method is faster) in wall-clock and in process-CPU
# time (steadier on a shared machine), visibility errors against the rays (0–255), peak
# memory, and the load average before and after.
#
#   scripts/shadows-bench.sh [PROXIMA_BENCH] [OUT_JSON]
# Environment: FILTER (a regex over the benchmark names, default every size).
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
def scene(b):
    blades = int(b["name"].split("blades:")[1].split("/")[0])
    return "city" if blades == 0 else f"grass {blades} blades"
print("Wall-clock ms (medians):")
print("| scene | triangles | occluder tris (today) | step 1 | step 2 | step 3 | step 3 today | speed-up "
      "| depth-image total | Embree BVH | Embree rays | ratio static | ratio with BVH | vis err depth-image "
      "| vis err today | max RSS MB |")
print("|" + " --- |" * 16)
for b in rows:
    g = lambda k: b.get(k, float("nan"))
    print(f"| {scene(b)} | {g('triangles'):,.0f} | {g('occluder_triangles'):,.0f} ({g('occluder_triangles_today'):,.0f}) "
          f"| {g('reference_ms'):.0f} | {g('reconstruct_ms'):.0f} | {g('shadow_ms'):.0f} | {g('shadow_today_ms'):.0f} "
          f"| {g('shadow_speedup'):.2f}x | {g('depth_image_ms'):.0f} | {g('bvh_ms'):.0f} | {g('rays_ms'):.0f} "
          f"| {g('ratio_static'):.2f} | {g('ratio_dynamic'):.2f} | {g('vis_error_rays'):.2f} "
          f"| {g('vis_error_rays_today'):.2f} | {g('max_rss_mb'):.0f} |")
print("\nProcess-CPU ms (medians):")
print("| scene | steps 1+2 | step 3 | step 3 today | speed-up | depth-image total | Embree BVH | Embree rays "
      "| ratio static | ratio with BVH | step 3 texels (today) | triangles drawn (today) |")
print("|" + " --- |" * 12)
for b in rows:
    g = lambda k: b.get(k, float("nan"))
    print(f"| {scene(b)} | {g('steps12_cpu_ms'):.0f} | {g('shadow_cpu_ms'):.0f} | {g('shadow_today_cpu_ms'):.0f} "
          f"| {g('shadow_speedup_cpu'):.2f}x | {g('depth_image_cpu_ms'):.0f} | {g('bvh_cpu_ms'):.0f} "
          f"| {g('rays_cpu_ms'):.0f} | {g('ratio_static_cpu'):.2f} | {g('ratio_dynamic_cpu'):.2f} "
          f"| {g('texels'):,.0f} ({g('texels_today'):,.0f}) | {g('triangles_drawn'):,.0f} ({g('triangles_drawn_today'):,.0f}) |")
PY
