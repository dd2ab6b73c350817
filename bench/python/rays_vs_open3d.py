#!/usr/bin/env python3
"""Batched ray casts from numpy: proxima's RayScene.cast against Open3D's
RaycastingScene.cast_rays (also Embree 3) on the same triangles and the same rays, side by
side in one run: repetitions interleaved, medians reported, both on the same worker-thread
count (--threads, 0 = all cores). Not part of ctest.

Needs Open3D for /usr/bin/python3: `apt-get install python3-open3d` (Debian 12; not in
scripts/install-deps.sh, only this benchmark uses it).

Debian 12's python3-open3d 0.16 misses every ray: Debian's Embree is built with ray masks
and Open3D leaves the mask 0. With --mask-shim auto (the default) the benchmark detects
that on one ray, builds bench/python/open3d_ray_mask.c (cc and Embree's headers) and runs
itself again with it preloaded: it sets the mask of every ray Open3D passes to Embree
(one store per ray, on Open3D's side of the timing). --mask-shim off reports the broken
baseline as it is.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python/rays_vs_open3d.py
"""

import argparse
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import proxima


SHIM_ENV = "PROXIMA_OPEN3D_RAY_MASK_SHIM"


def open3d_misses(o3d):
    """True when Open3D's cast misses a ray aimed straight at a triangle (the ray-mask bug)."""
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], np.float32)),
                        o3d.core.Tensor(np.array([[0, 1, 2]], np.uint32)))
    hit = scene.cast_rays(o3d.core.Tensor(np.array([[0, 0, 1, 0, 0, -1]], np.float32)))
    return not np.isfinite(hit["t_hit"].numpy()[0])


def rerun_with_shim():
    """Builds the shim and runs this script again with it preloaded."""
    source = pathlib.Path(__file__).resolve().with_name("open3d_ray_mask.c")
    library = pathlib.Path(tempfile.mkdtemp(prefix="open3d_ray_mask_")) / "open3d_ray_mask.so"
    build = subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-o", str(library), str(source), "-ldl"],
                           capture_output=True, text=True)
    if build.returncode != 0:
        print(f"rays_vs_open3d: Open3D misses every ray and the shim did not build:\n{build.stderr}"
              "(--mask-shim off reports the broken baseline)", file=sys.stderr)
        return 2
    env = dict(os.environ, LD_PRELOAD=" ".join(filter(None, [str(library), os.environ.get("LD_PRELOAD")])))
    env[SHIM_ENV] = str(library)
    return subprocess.run([sys.executable, *sys.argv], env=env).returncode


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="living-room")
    ap.add_argument("--rays", type=int, default=1_000_000)
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--threads", type=int, default=0, help="worker threads of both (0 = all cores)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--mask-shim", choices=("auto", "off"), default="auto",
                    help="preload open3d_ray_mask.c when Open3D misses every ray (auto) or never (off)")
    args = ap.parse_args()
    try:
        import open3d as o3d
    except ImportError:
        print("rays_vs_open3d: Open3D is not installed for this Python (apt-get install python3-open3d)",
              file=sys.stderr)
        return 2
    shimmed = SHIM_ENV in os.environ
    if args.mask_shim == "auto" and not shimmed and open3d_misses(o3d):
        return rerun_with_shim()

    scene = proxima.load_scene(args.scene)
    positions = np.ascontiguousarray(scene.positions)
    triangles = np.ascontiguousarray(scene.triangles)

    # Origins uniform in the scene's bounds shrunk by 10 % (inside the room), directions
    # uniform on the sphere.
    rng = np.random.default_rng(args.seed)
    lo, hi = np.array(scene.bounds[0]), np.array(scene.bounds[1])
    pad = 0.1 * (hi - lo)
    origins = rng.uniform(lo + pad, hi - pad, (args.rays, 3)).astype(np.float32)
    directions = rng.normal(size=(args.rays, 3)).astype(np.float32)
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    rays6 = o3d.core.Tensor(np.concatenate([origins, directions], axis=1))

    proxima.set_threads(args.threads)
    t0 = time.perf_counter()
    ours = proxima.RayScene(scene)
    ours_build = time.perf_counter() - t0
    t0 = time.perf_counter()
    theirs = o3d.t.geometry.RaycastingScene(nthreads=args.threads)
    theirs.add_triangles(o3d.core.Tensor(positions), o3d.core.Tensor(triangles))
    # Open3D commits (builds) its BVH on the first query: a one-ray cast here.
    theirs.cast_rays(rays6[:1], nthreads=args.threads)
    theirs_build = time.perf_counter() - t0

    a = ours.cast(origins, directions)
    b = theirs.cast_rays(rays6, nthreads=args.threads)
    b_ids = b["primitive_ids"].numpy().astype(np.int64)
    b_ids[b_ids == o3d.t.geometry.RaycastingScene.INVALID_ID] = -1
    same_id = np.mean(a["triangle"] == b_ids)
    hit = (a["triangle"] >= 0) & (b_ids >= 0)
    t_diff = np.max(np.abs(a["t"][hit] - b["t_hit"].numpy()[hit]) / np.maximum(a["t"][hit], 1e-6)) if hit.any() else 0
    n_diff = np.max(np.abs(a["normal"][hit] - b["primitive_normals"].numpy()[hit])) if hit.any() else 0

    # Wall time and the process's CPU time (all its threads) of each call: on a shared machine
    # the CPU time moves less with the other processes' load than the wall time does.
    ours_s, theirs_s, ours_cpu, theirs_cpu = [], [], [], []
    for _ in range(args.reps):
        for call, wall, cpu in ((lambda: ours.cast(origins, directions), ours_s, ours_cpu),
                                (lambda: theirs.cast_rays(rays6, nthreads=args.threads), theirs_s, theirs_cpu)):
            c0, t0 = time.process_time(), time.perf_counter()
            call()
            wall.append(time.perf_counter() - t0)
            cpu.append(time.process_time() - c0)
    m_ours, m_theirs = statistics.median(ours_s), statistics.median(theirs_s)

    print(f"scene {args.scene}: {scene.triangle_count} triangles; {args.rays} random rays from inside its "
          f"bounds; threads {proxima.threads()} (of {proxima.hardware_threads()}); load average "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}; {args.reps} interleaved repetitions")
    if shimmed:
        print("Open3D's ray mask set by the preloaded bench/python/open3d_ray_mask.c (Debian's Embree has ray "
              "masks, Open3D 0.16 leaves them 0)")
    print(f"agreement: same triangle id {100 * same_id:.4f} % of rays; hits: proxima "
          f"{100 * np.mean(a['triangle'] >= 0):.2f} %, Open3D {100 * np.mean(b_ids >= 0):.2f} %; over rays "
          f"both hit: max relative t difference {t_diff:.2e}, max normal difference {n_diff:.2e}")
    if np.mean(b_ids >= 0) < 0.5 * np.mean(a["triangle"] >= 0):
        # Debian's python3-open3d 0.16 with Debian's Embree 3.13 (built with EMBREE_RAY_MASK
        # ON) leaves the ray mask 0, so every ray misses: its times are then those of a query
        # that finds nothing, not a valid baseline.
        print("WARNING: Open3D misses where proxima hits: its cast is broken here (ray mask; see --mask-shim); "
              "the comparison below is not valid", file=sys.stderr)
    print()
    print("| | BVH build (s) | cast median (ms) | Mrays/s | min (ms) | max (ms) | CPU median (ms) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, build, s, cpu in (("proxima RayScene.cast", ours_build, ours_s, ours_cpu),
                                ("Open3D RaycastingScene.cast_rays", theirs_build, theirs_s, theirs_cpu)):
        med = statistics.median(s)
        print(f"| {name} | {build:.2f} | {1e3 * med:.1f} | {args.rays / med / 1e6:.2f} | {1e3 * min(s):.1f} | "
              f"{1e3 * max(s):.1f} | {1e3 * statistics.median(cpu):.1f} |")
    print()
    print(f"proxima / Open3D time: {m_ours / m_theirs:.3f} (below 1 = proxima faster); CPU time: "
          f"{statistics.median(ours_cpu) / statistics.median(theirs_cpu):.3f}; per repetition: "
          f"{' '.join(f'{a / b:.2f}' for a, b in zip(ours_s, theirs_s))}")
    print(f"load average at the end {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
