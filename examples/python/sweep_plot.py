#!/usr/bin/python3
"""Sweeps the env-map cube size and the temporal key-frame threshold on a built-in scene
through proxima.study and plots error against milliseconds per frame into a PNG.

  PYTHONPATH=build/release/python /usr/bin/python3 examples/python/sweep_plot.py --out sweep.png

Each point is one study run: the env-map methods' error over the reflector (mae, 0-255)
against their frame time (m_ms), one series per method over the cube sizes; temporal reuse's
error against full ray tracing (temporal_mae_avg) against its time per frame
(temporal_ms_avg), over the key-frame thresholds (the thesis' threshold policy alone:
keyframe_cost=0). Sizes are small so the sweep runs in about a minute
on two cores (seconds on a quiet one); times are those of the machine it ran on.
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import proxima  # noqa: E402
import proxima.study  # noqa: E402

METHODS = ("envmap", "rectified", "average", "layered")


def sweep_cube_sizes(scene, sizes, width, height):
    points = {m: [] for m in METHODS}
    for size in sizes:
        r = proxima.study.envmap_reflect(scene, compare=True, cube_size=size, width=width, height=height, reps=3)
        for m in METHODS:
            points[m].append((size, r["metrics"][f"{m}_ms"], r["metrics"][f"{m}_mae"]))
        print(f"cube {size}: " + ", ".join(f"{m} {r['metrics'][f'{m}_mae']:.2f}" for m in METHODS), flush=True)
    return points


def sweep_thresholds(scene, thresholds, width, height, frames):
    points = []
    for t in thresholds:
        # keyframe_cost=0: the thesis' threshold policy alone decides the key frames
        r = proxima.study.temporal_reflect(scene, path="0", compare=True, threshold=t, keyframe_cost=0.0,
                                           width=width, height=height, frames=frames)
        m = r["metrics"]
        points.append((t, m["temporal_ms_avg"], m["temporal_mae_avg"], m["keyframes"]))
        print(f"threshold {t}: mae {m['temporal_mae_avg']:.3f}, {m['keyframes']:.0f} key frames", flush=True)
    return points


def plot(cube_points, temporal_points, scene_name, out):
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
    for method, pts in cube_points.items():
        a.plot([p[1] for p in pts], [p[2] for p in pts], "o-", label=method)
        for size, ms, mae in pts:
            a.annotate(str(size), (ms, mae), fontsize=7, xytext=(3, 3), textcoords="offset points")
    a.set(title=f"env-map reflections on {scene_name}: cube size", xlabel="ms per frame",
          ylabel="MAE over the reflector (0-255)")
    a.legend()
    b.plot([p[1] for p in temporal_points], [p[2] for p in temporal_points], "o-", color="C4")
    for t, ms, mae, keys in temporal_points:
        b.annotate(f"{t:g} ({keys:.0f} keys)", (ms, mae), fontsize=7, xytext=(3, 3), textcoords="offset points")
    b.set(title=f"temporal reuse on {scene_name}: threshold", xlabel="ms per frame",
          ylabel="MAE vs full ray tracing (0-255)")
    for ax in (a, b):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True, help="PNG file to write")
    parser.add_argument("--scene", default="room-reflector", help="built-in scene with a reflector and a camera path")
    parser.add_argument("--width", type=int, default=256)
    parser.add_argument("--height", type=int, default=192)
    parser.add_argument("--frames", type=int, default=30, help="frames of the camera path (temporal sweep)")
    parser.add_argument("--cube-sizes", default="16,32,64,128,256")
    parser.add_argument("--thresholds", default="0.02,0.05,0.1,0.2,0.3,0.5")
    args = parser.parse_args()
    scene = proxima.load_scene(args.scene)
    cubes = sweep_cube_sizes(scene, [int(s) for s in args.cube_sizes.split(",")], args.width, args.height)
    temporal = sweep_thresholds(scene, [float(t) for t in args.thresholds.split(",")], args.width, args.height,
                                args.frames)
    plot(cubes, temporal, scene.name, args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    sys.exit(main())
