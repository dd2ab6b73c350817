"""load_scene, Scene, Camera, materials: what a scene holds and how bad input fails."""

import numpy as np
import pytest

import proxima


def test_builtin_scene_loads(cornell):
    assert cornell.name == "cornell"
    assert cornell.triangle_count > 0
    assert cornell.object_count == len(cornell.objects)
    assert sum(o.triangle_count for o in cornell.objects) == cornell.triangle_count
    assert "front" in cornell.cameras
    names = [name for name, _ in proxima.builtin_scenes()]
    assert "cornell" in names and "living-room" in names


def test_geometry_arrays_are_read_only_views(cornell):
    p = cornell.positions
    t = cornell.triangles
    assert p.dtype == np.float32 and p.shape == (cornell.vertex_count, 3)
    assert t.dtype == np.uint32 and t.shape == (cornell.triangle_count, 3)
    assert cornell.triangle_object.shape == (cornell.triangle_count,)
    assert cornell.triangle_material.shape == (cornell.triangle_count,)
    assert t.max() < cornell.vertex_count
    # Cornell interior: x in [-1, 1], y in [0, 2], z in [-1, 1] (scene/builtin_scenes.h).
    lo, hi = cornell.bounds
    assert lo[1] == pytest.approx(0.0, abs=1e-6) and hi[0] >= 1.0
    with pytest.raises(ValueError):
        p[0, 0] = 1.0


def test_cameras_by_name_and_index(cornell):
    a = cornell.camera("front", width=64, height=48)
    b = cornell.camera(0, width=64, height=48)
    assert (a.width, a.height) == (64, 48)
    assert a.position == b.position and a.forward == b.forward
    assert cornell.camera().position == a.position
    with pytest.raises(ValueError, match="--camera"):
        cornell.camera("no-such-camera")
    with pytest.raises(ValueError, match="--camera"):
        cornell.camera(99)


def test_camera_constructor_and_matrices():
    cam = proxima.Camera((0, 1, 3), (0, 1, 0), vfov_deg=45, width=32, height=16)
    assert cam.forward == pytest.approx((0, 0, -1), abs=1e-6)
    assert cam.right == pytest.approx((1, 0, 0), abs=1e-6)
    view = cam.view_matrix()
    assert view.shape == (4, 4) and view.dtype == np.float32
    # The camera position maps to the camera-space origin.
    assert view @ np.array([0, 1, 3, 1], np.float32) == pytest.approx([0, 0, 0, 1], abs=1e-6)
    with pytest.raises(ValueError, match="Camera"):
        proxima.Camera((0, 0, 0), (0, 0, 0))  # no view direction
    with pytest.raises(ValueError, match="Camera"):
        proxima.Camera((0, 0, 0), (0, 0, -1), vfov_deg=180)
    with pytest.raises(ValueError, match="position"):
        proxima.Camera((0, float("nan"), 0), (0, 0, -1))
    with pytest.raises(ValueError, match="target"):
        proxima.Camera((0, 0, 0), (0, 0))


def test_path_camera():
    scene = proxima.load_scene("bathroom")
    paths = {p.name: p for p in scene.camera_paths}
    assert "walk" in paths
    first = scene.path_camera("walk", 0, width=32, height=32)
    last = scene.path_camera("walk", paths["walk"].frames - 1, width=32, height=32)
    assert first.position != last.position
    with pytest.raises(ValueError, match="--path"):
        scene.path_camera("no-such-path", 0)
    with pytest.raises(ValueError, match="--frame"):
        scene.path_camera("walk", paths["walk"].frames)


def test_materials_are_editable_and_checked():
    scene = proxima.load_scene("cornell")
    mat = scene.materials[0]
    mat.specular = 0.25
    mat.gloss = 0.5
    mat.diffuse = (0.1, 0.2, 0.3)
    again = scene.materials[0]
    assert again.specular == 0.25 and again.gloss == 0.5
    assert again.diffuse == pytest.approx((0.1, 0.2, 0.3))
    with pytest.raises(ValueError, match="specular"):
        mat.specular = 1.5
    with pytest.raises(ValueError, match="gloss"):
        mat.gloss = float("nan")
    with pytest.raises(ValueError, match="diffuse"):
        mat.diffuse = (-1, 0, 0)
    assert scene.materials[0].specular == 0.25  # failed edits change nothing


def test_max_triangles():
    with pytest.raises(ValueError, match="max-triangles"):
        proxima.load_scene("cornell", max_triangles=10)
    assert proxima.load_scene("cornell", max_triangles=10**7).triangle_count > 10


def test_missing_file_raises_file_not_found(tmp_path):
    missing = tmp_path / "nothing.obj"
    with pytest.raises(FileNotFoundError, match="no such scene or file"):
        proxima.load_scene(str(missing))


def test_bad_scene_file_raises_value_error(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{ not json")
    with pytest.raises(ValueError, match="bad.json"):
        proxima.load_scene(str(bad))
    garbage = tmp_path / "garbage.obj"
    garbage.write_bytes(b"v 0 0 0\nf 1 2 3\n\x00\xff")
    with pytest.raises(ValueError, match="garbage.obj"):
        proxima.load_scene(str(garbage))
