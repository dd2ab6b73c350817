"""image_error and the EXR/PNG readers and writers."""

import numpy as np
import pytest

import proxima


def test_identical_images(tmp_path):
    a = np.random.default_rng(0).uniform(0, 1, (20, 30, 3)).astype(np.float32)
    e = proxima.image_error(a, a)
    assert e["mae"] == (0, 0, 0) and e["mae_avg"] == 0 and np.isinf(e["psnr_db"])
    assert e["pixels"] == 600
    assert e["error"].shape == (20, 30) and e["error"].dtype == np.float32
    assert e["heatmap"].shape == (20, 30, 3) and e["heatmap"].dtype == np.float32


def test_black_against_white():
    black = np.zeros((4, 5, 3), np.float32)
    white = np.ones((4, 5, 3), np.float32)
    e = proxima.image_error(black, white)
    assert e["mae"] == pytest.approx((255, 255, 255))
    assert e["max_abs"] == pytest.approx((255, 255, 255))
    assert e["psnr_db"] == pytest.approx(0.0, abs=1e-5)
    assert np.allclose(e["error"], 255, atol=1e-3)  # sRGB(1.0) · 255 in float32


def test_mask_limits_the_comparison():
    a = np.zeros((4, 4, 3), np.float32)
    b = a.copy()
    b[0, 0] = 1.0
    mask = np.zeros((4, 4), bool)
    mask[1:, :] = True
    e = proxima.image_error(a, b, mask=mask)
    assert e["pixels"] == 12 and e["mae_avg"] == 0
    assert proxima.image_error(a, b)["mae_avg"] > 0


def test_bad_images_raise():
    a = np.zeros((4, 4, 3), np.float32)
    with pytest.raises(ValueError, match="reference"):
        proxima.image_error(a, np.zeros((4, 5, 3), np.float32))
    with pytest.raises(ValueError, match="approx: expected a float32"):
        proxima.image_error(a.astype(np.float64), a)
    with pytest.raises(ValueError, match="approx"):
        proxima.image_error(np.zeros((4, 4), np.float32), a)
    nan = a.copy()
    nan[1, 1, 1] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        proxima.image_error(nan, a)
    with pytest.raises(ValueError, match="mask"):
        proxima.image_error(a, a, mask=np.ones((3, 3), bool))


def test_exr_round_trip(tmp_path):
    a = np.random.default_rng(2).normal(size=(7, 9, 3)).astype(np.float32)
    path = tmp_path / "a.exr"
    proxima.write_exr(str(path), a)
    assert np.array_equal(proxima.read_exr(str(path)), a)
    gray = a[:, :, 0].copy()
    proxima.write_exr(str(path), gray)
    assert np.array_equal(proxima.read_exr(str(path)), gray)


def test_png_round_trip(tmp_path):
    a = np.linspace(0, 1, 6 * 8 * 3, dtype=np.float32).reshape(6, 8, 3)
    path = tmp_path / "a.png"
    proxima.write_png(str(path), a)
    back = proxima.read_image(str(path))
    assert back.shape == (6, 8, 3)
    assert np.max(np.abs(back - a)) < 0.01  # 8-bit sRGB quantization


def test_missing_and_bad_files(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such file"):
        proxima.read_exr(str(tmp_path / "missing.exr"))
    bad = tmp_path / "bad.exr"
    bad.write_bytes(b"not an exr")
    with pytest.raises(ValueError, match="bad.exr"):
        proxima.read_exr(str(bad))
    with pytest.raises(ValueError, match="image"):
        proxima.write_exr(str(tmp_path / "x.exr"), np.zeros((2, 2, 5), np.float32))
    with pytest.raises(ValueError, match="1, 3 or 4 channels"):
        proxima.write_png(str(tmp_path / "x.png"), np.zeros((2, 2, 2), np.float32))
    with pytest.raises(ValueError, match="does not exist"):
        proxima.write_exr(str(tmp_path / "no" / "x.exr"), np.zeros((2, 2, 3), np.float32))
