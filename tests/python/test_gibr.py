"""proxima.GibrModel: built from synthetic photographs or from photographs given as arrays
with their cameras; novel views equal to `proxima gibr`'s (the study's arrays) on the same
settings."""

import numpy as np
import pytest

import proxima
import proxima.study

PHOTOS, PW, PH = 4, 64, 48
MODEL = dict(photo_width=PW, photo_height=PH, supersample=1, seed=3)


@pytest.fixture(scope="module")
def rooms():
    return proxima.load_scene("rooms")


@pytest.fixture(scope="module")
def model(rooms):
    return proxima.GibrModel(rooms, PHOTOS, item_buffer=True, **MODEL)


def test_shapes_and_dtypes(rooms, model):
    assert len(model.cameras) == len(model.photos) == PHOTOS
    for cam, photo in zip(model.cameras, model.photos):
        assert (cam.width, cam.height) == (PW, PH)
        assert photo.shape == (PH, PW, 3) and photo.dtype == np.float32 and photo.max() > 0
    st = model.stats
    assert st["photos"] == PHOTOS and st["polygons"] > 0 and st["samples"] > 0 and st["texel_m"] > 0
    cam = rooms.path_camera(0, 0, width=80, height=60)
    r = model.render(cam)
    assert r["color"].shape == (60, 80, 3) and r["color"].dtype == np.float32
    assert r["unseen"].shape == (60, 80) and r["unseen"].dtype == np.bool_
    assert r["unseen"].sum() == r["stats"]["holes"] <= r["stats"]["covered"]
    assert r["color"].max() > 0


def test_novel_view_equals_study(rooms, model):
    """views='photos': the study's first novel view is rendered from the first photograph's
    camera; its arrays hold that view for both mappings, bit for bit."""
    study = proxima.study.gibr(rooms, photos=PHOTOS, photo_width=PW, photo_height=PH, supersample=1, seed=3,
                               views="photos", frames=1, fps_repeat=1, photo_images=False)
    assert study["metrics"]["photos"] == PHOTOS
    a = study["arrays"]
    assert set(a) >= {"novel_vismap", "novel_itembuffer", "truth", "error_vismap"}
    v = model.render(model.cameras[0])
    i = model.render(model.cameras[0], mapping="itembuffer")
    assert np.array_equal(v["color"], a["novel_vismap"])
    assert np.array_equal(i["color"], a["novel_itembuffer"])
    assert a["truth"].shape == (PH, PW, 3)
    # its error against the study's ground truth is the study's (one view: the pooled MAE)
    assert proxima.image_error(v["color"], a["truth"])["mae_avg"] == study["metrics"]["mae_vismap"]


def test_given_photos_equal_synthetic(rooms, model):
    """The same photographs and cameras given as arrays build the same model: the same novel
    view bit for bit."""
    given = proxima.GibrModel(rooms, model.photos, model.cameras, **MODEL)
    assert given.stats["samples"] == model.stats["samples"]
    cam = rooms.path_camera(0, 3, width=80, height=60)
    assert np.array_equal(given.render(cam)["color"], model.render(cam)["color"])
    # the arrays are what is mapped: photographs at half the radiance give a view at about
    # half (the radiance maps store sRGB 8-bit samples clamped to [0, 1], and the lights'
    # pixels exceed 1, so only most pixels halve to within the 8-bit step)
    darker = proxima.GibrModel(rooms, [0.5 * p for p in model.photos], model.cameras, **MODEL)
    half, full = darker.render(cam)["color"], given.render(cam)["color"]
    assert np.median(np.abs(half - 0.5 * full)) < 1 / 255
    assert half.mean() < 0.6 * full.mean()


def test_bad_input(rooms, model):
    photos, cams = model.photos, model.cameras
    with pytest.raises(ValueError, match="cameras"):
        proxima.GibrModel(rooms, photos, **MODEL)
    with pytest.raises(ValueError, match="photos"):
        proxima.GibrModel(rooms, photos[:2], cams, **MODEL)
    with pytest.raises(ValueError, match="photos"):
        proxima.GibrModel(rooms, [photos[0][:10]] + photos[1:], cams, **MODEL)
    with pytest.raises(ValueError, match="photos"):
        proxima.GibrModel(rooms, [photos[0].astype(np.float64)] + photos[1:], cams, **MODEL)
    nan = photos[0].copy()
    nan[0, 0, 0] = np.nan
    with pytest.raises(ValueError, match="finite"):
        proxima.GibrModel(rooms, [nan] + photos[1:], cams, **MODEL)
    with pytest.raises(ValueError, match="--supersample"):
        proxima.GibrModel(rooms, 2, supersample=0)
    with pytest.raises(ValueError, match="--scene"):
        proxima.GibrModel(proxima.load_scene("cornell"), 2)
    with pytest.raises(ValueError, match="mapping"):
        proxima.GibrModel(rooms, photos, cams, **MODEL).render(cams[0], mapping="itembuffer")
    with pytest.raises(ValueError, match="^k:"):
        model.render(cams[0], k=0)
