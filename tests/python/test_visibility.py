"""proxima.VisibilityMaps: regions as polygon arrays, the label image and silhouette edges,
equal to `proxima visibility` (results.json) on the same scene, path and size."""

import json
import subprocess

import numpy as np
import pytest

import proxima

W, H, FRAMES = 96, 72, 3


@pytest.fixture(scope="module")
def rooms():
    return proxima.load_scene("rooms")


@pytest.fixture(scope="module")
def maps(rooms):
    return proxima.VisibilityMaps(rooms)


def shoelace(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


def test_shapes_and_invariants(rooms, maps):
    r = maps.trace(rooms.path_camera(0, 0, width=W, height=H))
    regions = r["regions"]
    assert len(regions) == r["stats"]["regions"] == len(r["region_polygon"]) > 1
    assert r["region_polygon"].dtype == np.int32 and r["region_merged"].dtype == np.int32
    area = 0.0
    for p in regions:
        assert p.dtype == np.float64 and p.ndim == 2 and p.shape[1] == 2 and p.shape[0] >= 3
        assert shoelace(p) > 0
        area += shoelace(p)
    assert abs(area - W * H) < 1e-6 * W * H  # the regions tile the image
    assert r["labels"].shape == (H, W) and r["labels"].dtype == np.int32
    polygons = len(maps.polygon_object)
    assert r["labels"].max() < polygons and r["labels"].min() >= -1
    # every label on the image is a polygon some region shows
    assert set(np.unique(r["labels"])) <= set(r["region_polygon"].tolist())
    assert r["edges"].dtype == np.float64 and r["edges"].shape[1:] == (2, 2)
    assert r["silhouette_edges"].shape == (r["stats"]["silhouette_edges"], 2, 2)
    assert r["check"]["passed"], r["check"]["reason"]
    assert maps.triangle_polygon.shape == (rooms.triangle_count,)
    assert maps.build_stats["polygons"] == polygons


def test_labels_agree_with_embree(rooms, maps):
    """Labels are polygon ids: away from region boundaries they are the polygon of the
    triangle Embree's item buffer sees (rasterize on the welded scene may differ only at
    boundaries, so the agreement is high but compared per pixel, not assumed)."""
    cam = rooms.path_camera(0, 1, width=W, height=H)
    r = maps.trace(cam)
    ids = proxima.render_reference(rooms, cam, bounces=0)["id"]
    expected = np.where(ids >= 0, maps.triangle_polygon[np.maximum(ids, 0)], -1)
    agree = np.mean(expected == r["labels"])
    assert agree > 0.97, agree


def test_equal_cli(rooms, maps, cli, tmp_path):
    """Per viewpoint: beams, regions, merged regions, visible polygons and silhouette edges
    of the command line's per-view table, and its Table 1 counts."""
    out = tmp_path / "vis"
    subprocess.run([cli, "visibility", "--scene", "rooms", "--width", str(W), "--height", str(H), "--frames",
                    str(FRAMES), "--no-images", "--out", str(out)], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    results = json.loads((out / "results.json").read_text())
    m = results["metrics"]
    for name in ("polygons", "cells", "faces", "edges", "vertices"):
        assert maps.build_stats[name] == m[name], name
    table = next(t for t in results["tables"] if t["title"].startswith("visibility maps of"))
    col = {c: i for i, c in enumerate(table["columns"])}
    assert len(table["rows"]) == FRAMES
    for frame, row in enumerate(table["rows"]):
        r = maps.trace(rooms.path_camera(0, frame, width=W, height=H))
        for name in ("beams", "regions", "merged_regions", "visible_polygons", "silhouette_edges"):
            assert r["stats"][name] == row[col[name]], (frame, name)
        assert float(r["check"]["passed"]) == row[col["selfcheck_pass"]]


def test_save_and_load(rooms, maps, tmp_path):
    path = tmp_path / "rooms.wp"
    maps.save(str(path))
    loaded = proxima.VisibilityMaps(rooms, load=path)
    cam = rooms.path_camera(0, 2, width=W, height=H)
    a, b = maps.trace(cam, check=False), loaded.trace(cam, check=False)
    assert "check" not in a
    assert np.array_equal(a["labels"], b["labels"])
    assert all(np.array_equal(p, q) for p, q in zip(a["regions"], b["regions"]))


def test_bad_input(rooms, maps, tmp_path):
    with pytest.raises(ValueError, match="missing.wp"):
        proxima.VisibilityMaps(rooms, load=tmp_path / "missing.wp")
    bad = tmp_path / "bad.wp"
    bad.write_bytes(b"not a winged pair")
    with pytest.raises(ValueError, match="bad.wp"):
        proxima.VisibilityMaps(rooms, load=bad)
    with pytest.raises(ValueError, match="check_rays"):
        maps.trace(rooms.path_camera(0, 0, width=W, height=H), check_rays=0)
    far = proxima.Camera((1e6, 1e6, 1e6), (0, 0, 0), (0, 1, 0), 60, W, H)
    with pytest.raises(ValueError):
        maps.trace(far)
