"""Reconstruction and soft shadows: proxima.reconstruct and proxima.SoftShadows against the
command line's `proxima shadows` (results.json) and the study's images, on the same settings."""

import json
import subprocess

import numpy as np
import pytest

import proxima
import proxima.study

# `proxima shadows` at a small size: out/ref/shadow maps 64 px, 3×3 light samples.
SIZE, N = 64, 3
STUDY = dict(sampling="nrr", light_samples=N, ref_res=SIZE, out_res=SIZE, shadow_res=SIZE)


@pytest.fixture(scope="module")
def city():
    return proxima.load_scene("city")


@pytest.fixture(scope="module")
def shadows(city):
    return proxima.SoftShadows(city, city.camera(width=SIZE, height=SIZE), light_samples=N, shadow_res=SIZE)


@pytest.fixture(scope="module")
def study(city):
    return proxima.study.shadows(city, **STUDY)


def test_soft_shadows_shapes_and_dtypes(shadows):
    r = shadows.render("nrr", ref_res=SIZE)
    assert r["lit"].shape == (SIZE, SIZE) and r["lit"].dtype == np.float32
    assert r["shadow"].shape == (SIZE, SIZE, 3) and r["shadow"].dtype == np.float32
    assert r["error"].shape == (SIZE, SIZE, 3) and r["error"].dtype == np.float32
    mask = shadows.receivers["mask"]
    assert mask.dtype == np.bool_ and mask.sum() == shadows.receivers["count"] > 0
    assert np.all(r["lit"][~mask] == 0) and np.all((r["lit"] >= 0) & (r["lit"] <= 1))
    # some receivers lit, some in shadow: the scene casts shadows at all
    assert r["lit"][mask].max() == 1 and r["lit"][mask].min() < 1
    assert shadows.light_samples.shape == (N * N, 3) and shadows.light_corners.shape == (4, 3)
    occ = r["occluders"]
    assert occ["positions"].dtype == np.float32 and occ["triangles"].dtype == np.uint32
    assert len(occ["triangles"]) == r["stats"]["occluder_triangles"] > 0
    assert occ["triangles"].max() < len(occ["positions"])


def test_soft_shadows_equal_cli(city, shadows, cli, tmp_path):
    """The errors, occluder triangles and samples of `proxima shadows` on the same settings,
    bit for bit (results.json holds them as written by the command line)."""
    out = tmp_path / "shadows"
    subprocess.run([cli, "shadows", "--scene", "city", "--sampling", "nrr", "--light-samples", str(N),
                    "--ref-res", str(SIZE), "--out-res", str(SIZE), "--shadow-res", str(SIZE), "--out", str(out)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    m = json.loads((out / "results.json").read_text())["metrics"]
    r = shadows.render("nrr", ref_res=SIZE)
    assert set(r["errors"]) == {k for k in m if k.startswith(("intensity_error", "visibility_error"))}
    for name, value in r["errors"].items():
        assert value == m[name], name
    assert r["stats"]["occluder_triangles"] == m["occluder_triangles"]
    assert r["stats"]["reference_samples"] == m["reference_samples"]
    assert shadows.receivers["count"] == m["receivers"]


def test_soft_shadow_images_equal_study(shadows, study):
    """The shadow and error images are the study's (its arrays), bit for bit."""
    r = shadows.render("nrr", ref_res=SIZE)
    arrays = study["arrays"]
    assert np.array_equal(r["shadow"], arrays["nrr_shadow"])
    assert np.array_equal(r["error"], arrays["nrr_error"])
    assert np.array_equal(shadows.truth()["shadow"], arrays["geometry_shadow"])
    assert np.array_equal(shadows.exact()["shadow"], arrays["rays_shadow"])


def test_geometry_sampling_is_the_truth(shadows):
    r = shadows.render("geometry")
    assert np.array_equal(r["lit"], shadows.truth()["lit"])
    assert r["errors"]["intensity_error_mean"] == 0 and r["errors"]["visibility_error_max"] == 0


def test_reconstruct_equals_the_occluders(city, shadows):
    """Reconstructing the light cameras' NRR images with planar runs merged gives the study's
    occluders: the same samples and triangle count (and, meshes concatenated, the same
    triangles); unmerged, more triangles."""
    r = shadows.render("nrr", ref_res=SIZE)
    cams = shadows.light_cameras("nrr", ref_res=SIZE)
    assert len(cams) == 4 and all(c.width == SIZE for c in cams)
    meshes = proxima.reconstruct(city, cams, "nrr-pixel", reconstruction="hybrid", merge_planar_runs=True)
    assert len(meshes) == 4
    unmerged = proxima.reconstruct(city, cams, "nrr-pixel", reconstruction="hybrid")
    assert sum(len(m["triangles"]) for m in unmerged) > sum(len(m["triangles"]) for m in meshes)
    assert sum(m["samples"] for m in meshes) == r["stats"]["reference_samples"]
    assert sum(len(m["triangles"]) for m in meshes) == r["stats"]["occluder_triangles"]
    offset, positions, triangles = 0, [], []
    for m in meshes:
        assert m["positions"].dtype == np.float32 and m["triangles"].dtype == np.uint32
        assert m["corners_from_h"] + m["corners_fitted"] > 0
        positions.append(m["positions"])
        triangles.append(m["triangles"] + offset)
        offset += len(m["positions"])
    assert np.array_equal(np.concatenate(positions), r["occluders"]["positions"])
    assert np.array_equal(np.concatenate(triangles), r["occluders"]["triangles"])


def test_reconstruct_conventional(city, shadows):
    cams = shadows.light_cameras("conventional", ref_res=SIZE)
    conv = proxima.reconstruct(city, cams[:1], "conventional", reconstruction="conventional")[0]
    images = proxima.sample_depth_images(city, cams[:1], "conventional")
    assert conv["samples"] == (images[0]["id"] >= 0).sum()
    # one vertex (with its normal) per sample, at most two triangles per 2×2 quad
    assert len(conv["positions"]) == len(conv["normals"]) == conv["samples"]
    assert 0 < len(conv["triangles"]) <= 2 * (SIZE - 1) ** 2
    assert "corners_from_h" not in conv


def test_bad_input(city, shadows):
    cam = city.camera(width=SIZE, height=SIZE)
    with pytest.raises(ValueError, match="--light-samples"):
        proxima.SoftShadows(city, cam, light_samples=0)
    with pytest.raises(ValueError, match="--light-size"):
        proxima.SoftShadows(city, cam, light_size=-1)
    with pytest.raises(ValueError, match="sampling"):
        shadows.render("nope")
    with pytest.raises(ValueError, match="--ref-res"):
        shadows.render("nrr", ref_res=2)
    with pytest.raises(ValueError, match="redundancy"):
        shadows.render("nrr", redundancy="nope")
    with pytest.raises(ValueError, match="reconstruction"):
        proxima.reconstruct(city, [cam], "conventional", reconstruction="nope")
    with pytest.raises(ValueError, match="layers"):
        proxima.reconstruct(city, [cam], "peeling", layers=0)
    assert proxima.SoftShadows(city, cam, light_samples=2, shadow_res=16, rays=False).exact() is None
