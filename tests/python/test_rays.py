"""RayScene.cast: batched ray casts from numpy arrays."""

import numpy as np
import pytest

import proxima


@pytest.fixture(scope="module")
def rays(cornell):
    return proxima.RayScene(cornell)


def f32(rows):
    return np.array(rows, dtype=np.float32)


def cornell_rays(rng, n):
    """n rays from random points inside the Cornell box in random directions (N×3 float32 each)."""
    origins = rng.uniform(-0.9, 0.9, (n, 3)).astype(np.float32)
    origins[:, 1] += 1.0
    return origins, rng.normal(size=(n, 3)).astype(np.float32)


def test_known_hits_and_misses(cornell, rays):
    # From the middle of the Cornell box: straight down onto the floor (y = 0) and out of its
    # open side (z = +1), where nothing is hit.
    h = rays.cast(f32([[0, 1, 0], [0, 1, 0]]), f32([[0, -1, 0], [0, 0, 1]]))
    assert set(h) == {"t", "triangle", "object", "normal", "uv"}
    assert h["t"].dtype == np.float32 and h["t"].shape == (2,)
    assert h["triangle"].dtype == np.int32 and h["object"].dtype == np.int32
    assert h["normal"].shape == (2, 3) and h["uv"].shape == (2, 2)
    assert h["t"][0] == pytest.approx(1.0, abs=1e-5)
    assert h["normal"][0] == pytest.approx([0, 1, 0], abs=1e-5)
    assert h["object"][0] == cornell.triangle_object[h["triangle"][0]]
    assert np.isinf(h["t"][1]) and h["triangle"][1] == -1 and h["object"][1] == -1
    assert np.all(h["normal"][1] == 0) and np.all(h["uv"][1] == 0)


def test_hit_points_lie_on_their_triangles(cornell, rays):
    origins, directions = cornell_rays(np.random.default_rng(1), 20000)
    h = rays.cast(origins, directions)
    hit = h["triangle"] >= 0
    assert hit.mean() > 0.5
    p = origins[hit] + h["t"][hit, None] * directions[hit]
    tri = cornell.triangles[h["triangle"][hit]]
    pos = cornell.positions
    u, v = h["uv"][hit, 0:1], h["uv"][hit, 1:2]
    q = (1 - u - v) * pos[tri[:, 0]] + u * pos[tri[:, 1]] + v * pos[tri[:, 2]]
    assert np.max(np.abs(p - q)) < 1e-4
    assert np.allclose(np.linalg.norm(h["normal"][hit], axis=1), 1.0, atol=1e-5)
    # Non-contiguous inputs give the same answers.
    both = np.concatenate([origins, directions], axis=1)
    h2 = rays.cast(both[:, :3], both[:, 3:])
    assert np.array_equal(h2["t"], h["t"]) and np.array_equal(h2["triangle"], h["triangle"])


def test_results_do_not_depend_on_the_batch(rays):
    # The batch is traced in its own coherent order; each ray's answer is its own: a shuffled
    # batch and the batch cast in two parts give the same bits.
    rng = np.random.default_rng(2)
    n = 30000
    origins, directions = cornell_rays(rng, n)
    h = rays.cast(origins, directions)
    perm = rng.permutation(n)
    shuffled = rays.cast(origins[perm], directions[perm])
    parts = [rays.cast(origins[s], directions[s]) for s in (slice(0, 1000), slice(1000, n))]
    for key in h:
        assert np.array_equal(shuffled[key], h[key][perm]), key
        assert np.array_equal(np.concatenate([p[key] for p in parts]), h[key]), key


def test_tmax_clips(rays):
    h = rays.cast(f32([[0, 1, 0]]), f32([[0, -1, 0]]), tmax=0.5)
    assert h["triangle"][0] == -1


def test_empty_batch(rays):
    h = rays.cast(np.zeros((0, 3), np.float32), np.zeros((0, 3), np.float32))
    assert h["t"].shape == (0,) and h["normal"].shape == (0, 3)


def test_bad_rays_raise(rays):
    o = f32([[0, 1, 0]])
    d = f32([[0, -1, 0]])
    with pytest.raises(ValueError, match="origins: expected a float32 array of shape \\(N, 3\\), got float64"):
        rays.cast(o.astype(np.float64), d)
    with pytest.raises(ValueError, match="directions"):
        rays.cast(o, d[:, :2])
    with pytest.raises(ValueError, match="origins"):
        rays.cast([[0, 1, 0]], d)
    with pytest.raises(ValueError, match="1 origins but 2 directions"):
        rays.cast(o, np.repeat(d, 2, axis=0))
    with pytest.raises(ValueError, match="origin 0 is not finite"):
        rays.cast(f32([[0, np.nan, 0]]), d)
    with pytest.raises(ValueError, match="direction 0 is zero"):
        rays.cast(o, f32([[0, 0, 0]]))
    with pytest.raises(ValueError, match="tmin"):
        rays.cast(o, d, tmin=-1)
