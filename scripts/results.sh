#!/usr/bin/env bash
# docs/RESULTS.md from a recorded set of runs: `proxima demo` (every technique at the demo's
# quick settings) plus what the demo does not measure — the reference's rays per second,
# the rasterizer's speed, the soft shadows' geometry shadow-map time and the viewer's frame
# rates. Each run writes its results.json under OUT; `proxima results merge` joins them into
# docs/results.json and `proxima results page` writes docs/RESULTS.md from that file alone,
# so the page can be regenerated (and is checked: ResultsPage.* in tests/eval) from the
# committed results.json on a fresh clone.
#
# Usage (from anywhere; the binary must be built):
#   scripts/results.sh                  # PROXIMA=build/release/proxima OUT=out/results THREADS=2
# About 3 minutes on 2 idle cores (9.5 minutes at load average 18). Timings move with the
# machine's load; errors do not.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${PROXIMA:-build/release/proxima}
out=${OUT:-out/results}
threads=${THREADS:-2}
if [ ! -x "$bin" ]; then
  echo "results.sh: $bin not found: build first (make build)" >&2
  exit 2
fi
rm -rf "$out"
mkdir -p "$out"
# The page names the commit the binary was built from: refuse a binary older than HEAD.
"$bin" bench trace --width 8 --height 8 --reps 1 --threads 1 --out "$out/probe" >/dev/null
built=$(sed -n 's/^  "commit": "\(.*\)",$/\1/p' "$out/probe/results.json")
head=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
if [ "$built" != "$head" ]; then
  echo "results.sh: $bin was built from commit $built, HEAD is $head: reconfigure and rebuild first" \
    "(cmake -S . -B build/release && cmake --build build/release --target proxima)" >&2
  exit 2
fi
if ! git diff --quiet HEAD -- src include apps 2>/dev/null; then
  echo "results.sh: warning: uncommitted changes in src/, include/ or apps/: the page names $head" >&2
fi
run_named() {  # NAME COMMAND...: stdout to OUT/NAME.log
  local name=$1
  shift
  echo "results.sh: $*" >&2
  "$@" >"$out/$name.log"
}

run_named demo "$bin" demo --threads "$threads" --out "$out/demo"
run_named bench_trace "$bin" bench trace --threads "$threads" --out "$out/bench_trace"
run_named bench_raster "$bin" bench raster --skip-agreement --threads "$threads" --out "$out/bench_raster"
run_named shadows "$bin" shadows --scene city --sampling geometry,nrr,conventional,peeling --light-size 1 \
  --light-samples 8 --ref-res 512 --out-res 256 --no-images --threads "$threads" --out "$out/shadows"
run_named bench_view "$bin" bench view --move-scale 2 --frames 10 --rounds 2 --error --threads "$threads" \
  --out "$out/bench_view"

runs=()
for name in demo bench_trace bench_raster shadows bench_view; do
  runs+=("$name=$out/$name/results.json")
done
"$bin" results merge "${runs[@]}" --out docs/results.json
"$bin" results page docs/results.json --out docs/RESULTS.md
