"""The techniques on cameras and arrays: shapes, dtypes, and values cross-checked against
the studies (proxima.study, equal to the command line's results.json by test_study.py)."""

import numpy as np
import pytest

import proxima
import proxima.study

METHODS = ("envmap", "rectified", "average", "layered")
W, H, CUBE = 64, 48, 32


@pytest.fixture(scope="module")
def room():
    return proxima.load_scene("room-reflector")


@pytest.fixture(scope="module")
def envmap(room):
    return proxima.EnvmapReflections(room, cube_size=CUBE)


def test_envmap_shapes_and_dtypes(room, envmap):
    camera = room.camera(width=W, height=H)
    assert envmap.reflectors and envmap.layer_count == 3
    assert len(envmap.groups) == 1 and envmap.groups[0]["reflectors"] == envmap.reflectors
    assert envmap.groups[0]["average_distance_m"] > 0
    for method in METHODS:
        r = envmap.render(camera, method)
        assert r["color"].shape == (H, W, 3) and r["color"].dtype == np.float32
        assert r["triangle"].shape == (H, W) and r["triangle"].dtype == np.int32
        assert r["object"].shape == (H, W) and r["object"].dtype == np.int32
        on = r["triangle"] >= 0
        assert on.sum() == r["stats"]["pixels"] > 0
        assert np.all(r["color"][~on] == 0) and r["color"][on].max() > 0
        assert np.all(r["object"][~on] == -1)
        assert r["stats"]["lookups"] >= r["stats"]["pixels"]


def test_envmap_error_equals_study(room, envmap):
    """The method's frame (the one-bounce reference outside the reflector, the method on it),
    judged on the pixels both see a reflector, gives the study's m_mae bit for bit."""
    camera = room.camera(width=W, height=H)
    ref = proxima.render_reference(room, camera, bounces=1)
    study = proxima.study.envmap_reflect(room, compare=True, width=W, height=H, cube_size=CUBE, reps=1)
    tri_object = room.triangle_object
    ref_on_reflector = np.isin(np.where(ref["id"] >= 0, tri_object[np.maximum(ref["id"], 0)], -1),
                               envmap.reflectors) & (ref["id"] >= 0)
    for method in METHODS:
        r = envmap.render(camera, method)
        on = r["triangle"] >= 0
        frame = ref["color"].copy()
        frame[on] = r["color"][on]
        mae = proxima.image_error(frame, ref["color"], mask=(on & ref_on_reflector).astype(np.uint8))["mae_avg"]
        assert mae == study["metrics"][f"{method}_mae"], method


def test_envmap_bad_input(room):
    with pytest.raises(ValueError, match="cube-size"):
        proxima.EnvmapReflections(room, cube_size=0)
    with pytest.raises(ValueError, match="edge"):
        proxima.EnvmapReflections(room, cube_size=8, edge="nope")
    with pytest.raises(ValueError, match="reflective"):
        proxima.EnvmapReflections(proxima.load_scene("rooms"), cube_size=8)
    e = proxima.EnvmapReflections(room, cube_size=8, layers=1)
    with pytest.raises(ValueError, match="method"):
        e.render(room.camera(width=8, height=8), "nope")


def test_temporal_steps_equal_study_per_frame(room):
    """Stepping the path's frames gives, frame by frame, the study's key frames, reflective
    and recomputed percentages (its "Per frame" table), bit for bit."""
    w, h = 64, 48
    study = proxima.study.temporal_reflect(room, path="0", width=w, height=h, threshold=0.2)
    table = next(t for t in study["tables"] if t["title"] == "Per frame")
    col = {c: i for i, c in enumerate(table["columns"])}
    path = room.camera_paths[0]
    assert len(table["rows"]) == path.frames
    t = proxima.TemporalReflections(room, threshold=0.2)
    keys = 0
    for i, row in enumerate(table["rows"]):
        r = t.step(room.path_camera(0, i, width=w, height=h))
        st = r["stats"]
        assert r["color"].shape == (h, w, 3) and r["color"].dtype == np.float32
        assert r["reflective"].shape == (h, w) and r["reflective"].dtype == np.bool_
        assert r["reuse"].shape == (h, w) and r["reuse"].dtype == np.uint8
        assert r["reflective"].sum() == st["reflective"]
        assert np.all(r["reuse"][~r["reflective"]] == 0)
        assert float(st["key"]) == row[col["key"]], i
        assert 100.0 * st["reflective"] / (w * h) == row[col["reflective_pct"]], i
        if not st["key"]:
            assert 100.0 * st["recompute_fraction"] == row[col["recompute_pct"]], i
            assert (r["reuse"] != 0).sum() == st["recomputed"]
        keys += st["key"]
    assert t.frames == path.frames
    assert keys == study["metrics"]["keyframes"]


def test_temporal_bad_input(room):
    with pytest.raises(ValueError, match="threshold"):
        proxima.TemporalReflections(room, threshold=2.0)
    with pytest.raises(ValueError, match="edge-rule"):
        proxima.TemporalReflections(room, edge_rule="nope")
    with pytest.raises(ValueError, match="learn-error"):
        proxima.TemporalReflections(room, learn_error=-1.0)
    with pytest.raises(ValueError, match="refine-error"):
        proxima.TemporalReflections(room, refine_error=-1.0)


def test_temporal_feedback_traces_more(room):
    """The observed-error options reach the method: with both at 0 every reused pixel next to
    or projecting into an observed error is traced, so more pixels than without."""
    w, h = 64, 48
    recomputed = {}
    for name, kw in (("off", {}), ("on", {"refine_error": 0.0, "learn_error": 0.0})):
        t = proxima.TemporalReflections(room, **kw)
        total, added = 0, 0
        for i in range(4):
            st = t.step(room.path_camera(0, i, width=w, height=h))["stats"]
            total += st["recomputed"]
            added += st["refined"] + st["learned"]
        recomputed[name] = (total, added)
    assert recomputed["off"][1] == 0
    assert recomputed["on"][1] > 0
    assert recomputed["on"][0] > recomputed["off"][0]


def test_cluster_equals_study(room):
    """One camera: the clusters, texels, triangles drawn and occlusion errors of the study
    (`proxima reflect --method cluster --compare`) on the same camera and settings."""
    w, h = 64, 48
    r = proxima.cluster_reflections(room, room.camera(width=w, height=h), reference=True)
    assert r["color"].shape == (h, w, 3) and r["color"].dtype == np.float32
    assert r["reference"].shape == (h, w, 3) and r["reference"].dtype == np.float32
    st = r["stats"]
    assert st["clusters"] > 0 and st["reflective_samples"] > 0
    # only the reflections differ: identical where the frame shows no reflective surface
    assert np.count_nonzero(np.any(r["color"] != r["reference"], axis=-1)) <= st["reflective_samples"]
    m = proxima.study.cluster_reflect(room, compare=True, width=w, height=h)["metrics"]
    assert st["clusters"] == m["clusters_avg"]
    assert st["texels"] == m["texels_avg"]
    assert st["triangles_drawn"] == m["triangles_drawn_avg"]
    assert st["shaded_texels"] == m["shaded_texels_avg"]
    assert 100.0 * st["env_fallback_samples"] / st["reflective_samples"] == m["env_fallback_pct_avg"]
    assert 100.0 * st["occlusion_error_samples"] / st["reflective_samples"] == m["occlusion_error_pct_avg"]


def test_cluster_bad_input(room):
    with pytest.raises(ValueError, match="--ss"):
        proxima.cluster_reflections(room, room.camera(width=8, height=8), supersample=0)


@pytest.mark.parametrize("method", ["conventional", "nrr-pixel", "peeling"])
def test_depth_images_equal_study_files(cornell, tmp_path, method):
    """The depth and id images equal, bit for bit, the EXRs the sampling study writes for the
    same view set."""
    w = h = 48
    views = proxima.sampling_views(cornell, width=w, height=h)
    assert len(views["corners"]) == 3
    if method == "peeling":
        images = proxima.sample_depth_images(cornell, [views["centroid"]], method, layers=3)
    else:
        images = proxima.sample_depth_images(cornell, views["corners"], method)
    assert len(images) == 3
    r = proxima.study.sampling(cornell, out_dir=tmp_path, method=method, width=w, height=h, frames=4, reps=1)
    for i, image in enumerate(images):
        assert image["depth"].shape == (h, w) and image["depth"].dtype == np.float32
        assert image["id"].shape == (h, w) and image["id"].dtype == np.int32
        assert image["color"].shape == (h, w, 3) and image["normal"].shape == (h, w, 3)
        depth_file = next(f for role, f in r["images"].items() if role.endswith(f"{i}_depth"))
        id_file = next(f for role, f in r["images"].items() if role.endswith(f"{i}_id"))
        assert np.array_equal(proxima.read_exr(str(tmp_path / depth_file)), image["depth"])
        assert np.array_equal(proxima.read_exr(str(tmp_path / id_file)), image["id"].astype(np.float32))
    assert (images[0]["id"] >= 0).any()


def test_depth_images_bad_input(cornell):
    cam = cornell.camera(width=8, height=8)
    with pytest.raises(ValueError, match="method"):
        proxima.sample_depth_images(cornell, [cam], "nope")
    with pytest.raises(ValueError, match="layers"):
        proxima.sample_depth_images(cornell, [cam], "peeling")
    with pytest.raises(ValueError, match="views"):
        proxima.sampling_views(cornell, views="nope")
