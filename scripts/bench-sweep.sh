#!/usr/bin/env bash
# The sweep's scaling and scheduling overhead (docs/cli.md "Sweeps"; not a test):
#  1. bench/sweep/spp_grid.json (24 reference renders whose cost spans 144×) on 1 and on 2
#     MPI ranks, 1 thread per rank, alternating, REPS times each: wall seconds and speed-up.
#  2. bench/sweep/tiny_items.json (40 near-empty items) on 2 ranks: the time per item the
#     ranks spend outside study calls (scene load included in the calls), i.e.
#     ((wall − wall of a rerun with every item finished) × ranks − Σ item seconds) / items.
# Usage: scripts/bench-sweep.sh [build/release/proxima] [REPS]
set -euo pipefail
bin=${1:-build/release/proxima}
reps=${2:-2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
run() {  # ranks manifest out [keep] → wall seconds; keep: resume into out's items
  local start end
  [ "${4:-}" = keep ] || rm -rf "$3"
  start=$(date +%s.%N)
  mpirun --oversubscribe -np "$1" "$bin" sweep "$2" --threads 1 --out "$3" >/dev/null 2>"$3.log" || true
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
item_seconds() {  # out → Σ item seconds
  /usr/bin/python3 -c 'import json,sys,glob; print(sum(json.load(open(f))["seconds"] for f in glob.glob(sys.argv[1]+"/items/*/item.json")))' "$1"
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
declare -a w1 w2
for r in $(seq "$reps"); do
  w1+=("$(run 1 bench/sweep/spp_grid.json "$tmp/np1")")
  w2+=("$(run 2 bench/sweep/spp_grid.json "$tmp/np2")")
  echo "rep $r: 1 rank ${w1[-1]} s (items $(item_seconds "$tmp/np1") s), 2 ranks ${w2[-1]} s (items $(item_seconds "$tmp/np2") s), load $(cut -d' ' -f1 /proc/loadavg)"
done
med() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
m1=$(med "${w1[@]}"); m2=$(med "${w2[@]}")
echo "spp_grid (24 items): 1 rank ${m1} s, 2 ranks ${m2} s, speed-up $(echo "$m1 / $m2" | bc -l | cut -c1-5)x"
wt=$(run 2 bench/sweep/tiny_items.json "$tmp/tiny")
st=$(item_seconds "$tmp/tiny")
ws=$(run 2 bench/sweep/tiny_items.json "$tmp/tiny" keep)  # every item finished: start-up, merge, exit
echo "tiny_items (40 items, 2 ranks): wall ${wt} s, Σ items ${st} s, rerun with all 40 finished ${ws} s;" \
  "outside the study calls: $(echo "(($wt - $ws) * 2 - $st) * 1000 / 40" | bc -l | cut -c1-6) ms per item" \
  "(start-up and merge excluded)"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
