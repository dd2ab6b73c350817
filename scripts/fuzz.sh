#!/usr/bin/env bash
# Runs one libFuzzer target for a fixed time: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags]
# TARGET is a fuzz/<TARGET>_fuzz.cpp (scene_file, camera_path, gibr_cameras, photo_bin, part_bin, obj, ply, gltf,
# png, jpeg, exr, winged_pair, results), or
# `all` to run each in turn. Builds build/fuzz (clang, ASan + UBSan + libFuzzer) and the
# seeds (scripts/fuzz_seeds.sh) when needed; the corpus grows in build/fuzz/corpus/TARGET,
# crashes land in build/fuzz/artifacts/TARGET/; fuzz/regressions/TARGET/ (inputs of fixed
# findings) is replayed as part of the corpus. Exits non-zero on any finding (crash, leak,
# sanitizer report, timeout, out-of-memory) and prints the execution count.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags]}
seconds=${2:?usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags]}
shift 2
build=${FUZZ_BUILD:-build/fuzz}
jobs=${JOBS:-2}

if [ "$target" = all ]; then
  for src in fuzz/*_fuzz.cpp; do
    t=$(basename "$src" _fuzz.cpp)
    "$0" "$t" "$seconds" "$@"
  done
  exit 0
fi
[ -f "fuzz/${target}_fuzz.cpp" ] || { echo "fuzz.sh: no fuzz/${target}_fuzz.cpp" >&2; exit 2; }

if [ ! -f "$build/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  CXX=clang++ CC=clang cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPROXIMA_FUZZ=ON \
    -DPROXIMA_BUILD_TESTS=OFF -DPROXIMA_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
fi
cmake --build "$build" -j "$jobs" --target "${target}_fuzz" proxima >/dev/null

seeds=$build/seeds
[ -d "$seeds/$target" ] || scripts/fuzz_seeds.sh "$seeds" "$build/proxima"
corpus=$build/corpus/$target
artifacts=$build/artifacts/$target/
mkdir -p "$corpus" "$artifacts"
dict=()
case $target in scene_file | camera_path) dict=(-dict=fuzz/scene.dict) ;; results | winged_pair) dict=(-dict=fuzz/$target.dict) ;; gltf) dict=(-dict=fuzz/gltf.dict) ;; esac

# Inputs of fixed findings (fuzz/regressions/TARGET/, read-only: new units go to $corpus).
regressions=()
[ -d "fuzz/regressions/$target" ] && regressions=("fuzz/regressions/$target")
log=$build/$target.log
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan.supp}
set +e
begin=$SECONDS
"$build/${target}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$artifacts" "${dict[@]}" "$@" "$corpus" "$seeds/$target" "${regressions[@]}" >"$log" 2>&1
status=$?
set -e
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
echo "fuzz: $target: ${execs:-?} executions in $((SECONDS - begin)) s, exit $status (log: $log)"
if [ $status -ne 0 ]; then
  grep -E "ERROR|SUMMARY|invariant|Test unit written" "$log" | head -20 >&2
  exit 1
fi
