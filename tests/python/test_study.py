"""proxima.study: the functions generated from the study catalog, their metrics equal to the
command line's results.json on the same settings, and bad options as ValueError."""

import importlib.util
import json
import math
import pathlib
import subprocess

import numpy as np
import pytest

import proxima
import proxima.study

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _timing_rule():
    """The rule scripts/compare-demo.py uses to tell timings from deterministic metrics."""
    spec = importlib.util.spec_from_file_location("compare_demo", ROOT / "scripts" / "compare-demo.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.TIMING


TIMING = _timing_rule()


@pytest.fixture(scope="module")
def room():
    return proxima.load_scene("room-reflector")


def cli_flags(options):
    flags = []
    for name, value in options.items():
        flag = "--" + name.replace("_", "-")
        if value is True:
            flags.append(flag)
        elif value is not False:
            flags += [flag, str(value)]
    return flags


def cli_metrics(cli, tmp_path, command, scene, options):
    out = tmp_path / "cli"
    subprocess.run([cli, *command, "--scene", scene, "--out", str(out), *cli_flags(options)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return json.loads((out / "results.json").read_text())["metrics"]


def assert_same_metrics(python, cli):
    """Every deterministic metric equal; results.json writes non-finite numbers as null."""
    assert set(python) == set(cli)
    compared = 0
    for name, value in cli.items():
        if TIMING.search(name):
            continue
        compared += 1
        if value is None:
            assert not math.isfinite(python[name]), name
        else:
            assert python[name] == value, name
    assert compared > 5


ENVMAP = dict(compare=True, width=64, height=48, cube_size=32, reps=1)
TEMPORAL = dict(path="0", compare=True, frames=6, width=96, height=72, threshold=0.2)


def test_catalog_lists_every_study():
    catalog = proxima.study.catalog()
    names = [s["name"] for s in catalog]
    assert "envmap_reflect" in names and "temporal_reflect" in names
    for s in catalog:
        assert callable(getattr(proxima.study, s["name"]))
        doc = getattr(proxima.study, s["name"]).__doc__
        assert s["summary"] in doc
        for o in s["options"]:
            assert o["type"] in ("bool", "int", "float", "string")
            assert o["name"] in doc
            # the defaults are the ones the study resolves
            assert proxima.study.options(s["name"])[o["name"]] == o["default"] or (
                isinstance(o["default"], float) and math.isnan(o["default"]))


def test_envmap_metrics_equal_cli(room, cli, tmp_path):
    r = proxima.study.envmap_reflect(room, **ENVMAP)
    assert set(r) == {"metrics", "tables", "images", "arrays"}
    assert r["images"] == {}
    assert r["tables"] and {"title", "columns", "rows"} <= set(r["tables"][0])
    assert all(len(row) == len(r["tables"][0]["columns"]) for row in r["tables"][0]["rows"])
    assert r["metrics"]["rectified_mae"] > 0
    assert_same_metrics(r["metrics"], cli_metrics(cli, tmp_path, ["reflect"], "room-reflector", ENVMAP))


def test_temporal_metrics_equal_cli(room, cli, tmp_path):
    steps = []
    r = proxima.study.temporal_reflect(room, progress=lambda *a: steps.append(a), **TEMPORAL)
    assert steps
    assert r["metrics"]["frames"] == 6
    assert_same_metrics(r["metrics"],
                        cli_metrics(cli, tmp_path, ["reflect", "--method", "temporal"], "room-reflector", TEMPORAL))


def test_images_written_into_out_dir(room, tmp_path):
    r = proxima.study.envmap_reflect(room, out_dir=tmp_path / "out", width=32, height=24, cube_size=16, reps=1)
    assert r["images"]
    for file in r["images"].values():
        assert (tmp_path / "out" / file).stat().st_size > 0
    # every image written is also returned as an array, under the same role
    assert set(r["arrays"]) == set(r["images"])
    for role, array in r["arrays"].items():
        assert array.shape == (24, 32, 3) and array.dtype == np.float32, role


def test_images_as_arrays_equal_the_files_and_render(cornell, tmp_path):
    """The reference study's arrays: the linear color, depth and ids it writes as EXR, bit
    for bit, with or without out_dir; equal to render_reference on the same settings."""
    options = dict(camera="front", width=40, height=30, spp=2, light_samples=2)
    without = proxima.study.reference(cornell, **options)
    assert without["images"] == {}
    a = without["arrays"]
    assert {"color", "color_linear", "depth", "normal", "triangle_id"} <= set(a)
    assert a["depth"].shape == (30, 40) and a["color_linear"].shape == (30, 40, 3)
    r = proxima.study.reference(cornell, out_dir=tmp_path, **options)
    for role in ("color_linear", "depth", "normal", "triangle_id"):
        assert np.array_equal(a[role], r["arrays"][role]), role
        assert np.array_equal(proxima.read_exr(str(tmp_path / r["images"][role])), a[role]), role
    ref = proxima.render_reference(cornell, cornell.camera("front", width=40, height=30), spp=2, light_samples=2)
    assert np.array_equal(a["color_linear"], ref["color"])
    assert np.array_equal(a["color"], ref["color"])  # the PNG's image before encoding
    assert np.array_equal(a["triangle_id"], ref["id"].astype(np.float32))


def test_bad_options_raise_value_error(room):
    with pytest.raises(ValueError, match="no_such_option"):
        proxima.study.envmap_reflect(room, no_such_option=1)
    with pytest.raises(ValueError, match="cube_size"):
        proxima.study.envmap_reflect(room, cube_size="big")
    with pytest.raises(ValueError, match="cube_size"):
        proxima.study.envmap_reflect(room, cube_size=[1])
    with pytest.raises(ValueError, match="cube-size"):  # the study's own range check names the flag
        proxima.study.envmap_reflect(room, cube_size=0)
    with pytest.raises(ValueError, match="method"):
        proxima.study.envmap_reflect(room, method="nope")
    with pytest.raises(ValueError):
        proxima.study.temporal_reflect(room, path="no-such-path", width=16, height=16)
    with pytest.raises(ValueError):
        proxima.study.options("no_such_study")
