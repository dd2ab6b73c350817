#!/bin/sh
# Soft shadows from depth images against Embree shadow rays, both in one run (interleaved
# repetitions, medians; bench/shadows_crossover_bench.cpp): city and grass from 50k to 20M
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
def table(title, columns):
    """columns: (header, format) pairs; a format names counters in braces."""
    print(f"\n{title}\n| scene | " + " | ".join(h for h, _ in columns) + " |")
    print("|" + " --- |" * (len(columns) + 1))
    for b in rows:
        g = {k: v for k, v in b.items() if isinstance(v, (int, float))}
        print(f"| {scene(b)} | " + " | ".join(f.format(**g) for _, f in columns) + " |")
table("Wall-clock ms (medians):", [
    ("triangles", "{triangles:,.0f}"), ("occluder tris (today)", "{occluder_triangles:,.0f} ({occluder_triangles_today:,.0f})"),
    ("step 1", "{reference_ms:.0f}"), ("step 2", "{reconstruct_ms:.0f}"), ("step 3", "{shadow_ms:.0f}"),
    ("step 3 today", "{shadow_today_ms:.0f}"), ("speed-up", "{shadow_speedup:.2f}x"),
    ("depth-image total", "{depth_image_ms:.0f}"), ("Embree BVH", "{bvh_ms:.0f}"), ("Embree rays", "{rays_ms:.0f}"),
    ("ratio static", "{ratio_static:.2f}"), ("ratio with BVH", "{ratio_dynamic:.2f}"),
    ("vis err depth-image", "{vis_error_rays:.2f}"), ("vis err today", "{vis_error_rays_today:.2f}"),
    ("max RSS MB", "{max_rss_mb:.0f}")])
table("Process-CPU ms (medians):", [
    ("steps 1+2", "{steps12_cpu_ms:.0f}"), ("step 3", "{shadow_cpu_ms:.0f}"), ("step 3 today", "{shadow_today_cpu_ms:.0f}"),
    ("speed-up", "{shadow_speedup_cpu:.2f}x"), ("depth-image total", "{depth_image_cpu_ms:.0f}"),
    ("Embree BVH", "{bvh_cpu_ms:.0f}"), ("Embree rays", "{rays_cpu_ms:.0f}"), ("ratio static", "{ratio_static_cpu:.2f}"),
    ("ratio with BVH", "{ratio_dynamic_cpu:.2f}"), ("step 3 texels (today)", "{texels:,.0f} ({texels_today:,.0f})"),
    ("triangles drawn (today)", "{triangles_drawn:,.0f} ({triangles_drawn_today:,.0f})")])
PY
