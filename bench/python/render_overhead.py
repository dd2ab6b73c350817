#!/usr/bin/env python3
"""Overhead of the Python module: proxima.render_reference (512², the scene's first camera,
default sampling, BVH already built) against the same library calls in C++
(BM_ReferenceView in bench/reference_view_bench.cpp: item buffer + reference image), in
one run: the two alternate, each repetition a batch of at least --min-time seconds (mean
per call), medians over the repetitions reported. Not part of ctest.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python/render_overhead.py \
        --bench build/release/proxima_bench [--scene cornell|living-room]
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import proxima

SCENES = {"cornell": 0, "living-room": 1}


def cpp_ms(bench, scene, min_time):
    out = subprocess.run(
        [bench, f"--benchmark_filter=^BM_ReferenceView/{SCENES[scene]}/real_time$", f"--benchmark_min_time={min_time}",
         "--benchmark_format=json"], check=True, capture_output=True, text=True).stdout
    run = json.loads(out)["benchmarks"][0]
    assert run["time_unit"] == "ms"
    return run["real_time"], run["iterations"]


def python_ms(scene, camera, min_time):
    calls = 0
    t0 = time.perf_counter()
    while True:
        proxima.render_reference(scene, camera)
        calls += 1
        elapsed = time.perf_counter() - t0
        if elapsed >= min_time:
            return 1e3 * elapsed / calls, calls


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bench", default="build/release/proxima_bench", help="the proxima_bench binary")
    ap.add_argument("--scene", default="cornell", choices=sorted(SCENES))
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--min-time", type=float, default=1.0, help="seconds per batch")
    args = ap.parse_args()

    scene = proxima.load_scene(args.scene)
    camera = scene.camera(None, width=512, height=512)
    proxima.render_reference(scene, camera)  # builds the BVH, starts the worker threads
    py, cpp = [], []
    for _ in range(args.reps):
        py.append(python_ms(scene, camera, args.min_time)[0])
        cpp.append(cpp_ms(args.bench, args.scene, args.min_time)[0])
    m_py, m_cpp = statistics.median(py), statistics.median(cpp)
    print(f"scene {args.scene} ({scene.triangle_count} triangles), 512x512, default sampling; "
          f"{args.reps} interleaved repetitions of >= {args.min_time} s; threads {proxima.threads()}; "
          f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print()
    print("| | median ms per render | min | max |")
    print("| --- | --- | --- | --- |")
    print(f"| Python proxima.render_reference | {m_py:.2f} | {min(py):.2f} | {max(py):.2f} |")
    print(f"| C++ item buffer + render_reference | {m_cpp:.2f} | {min(cpp):.2f} | {max(cpp):.2f} |")
    print()
    print(f"Python / C++: {m_py / m_cpp:.4f} ({100 * (m_py / m_cpp - 1):+.2f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
