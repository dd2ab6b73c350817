// image_error (eval/image_error.h, the functions every command reports with) and the image
// readers and writers (core/image_io.h).
#include "arrays.h"
#include "bindings.h"
#include "proxima/core/image_io.h"
#include "proxima/eval/image_error.h"

namespace proxima::python {

namespace {

py::dict image_error_py(py::handle approx_obj, py::handle reference_obj, py::handle mask_obj, float heatmap_max) {
  const ImageF approx = checked_image(approx_obj, "approx", 3);
  const ImageF reference = checked_image(reference_obj, "reference", 3);
  check_finite(approx.data().data(), approx.data().size(), "approx");
  check_finite(reference.data().data(), reference.data().size(), "reference");
  if (approx.width() != reference.width() || approx.height() != reference.height())
    fail_input("image_error: approx is " + describe(approx_obj) + " but reference is " + describe(reference_obj));
  std::optional<ImageU8> mask;
  if (!mask_obj.is_none()) {
    const auto m = py::array::ensure(mask_obj);
    if (!m || m.ndim() != 2 || m.shape(0) != approx.height() || m.shape(1) != approx.width())
      fail_input("mask: expected an array of shape (H, W) = (" + std::to_string(approx.height()) + ", " +
                 std::to_string(approx.width()) + "), got " + describe(mask_obj));
    const auto b = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(m);
    if (!b) throw py::error_already_set();
    mask.emplace(approx.width(), approx.height(), 1);
    for (size_t i = 0; i < mask->data().size(); ++i) mask->data()[i] = b.data()[i] ? 1 : 0;
  }
  if (!(heatmap_max > 0.0f) || !std::isfinite(heatmap_max)) fail_input("heatmap_max: must be positive and finite");
  ImageError e;
  ImageF error, heat;
  {
    py::gil_scoped_release release;
    const ImageU8* m = mask ? &*mask : nullptr;
    e = compare_images(approx, reference, m);
    error = error_image(approx, reference, m);
    heat = error_heatmap(error, heatmap_max, m);
  }
  py::dict out;
  out["mae"] = py::make_tuple(e.mae[0], e.mae[1], e.mae[2]);
  out["max_abs"] = py::make_tuple(e.max_abs[0], e.max_abs[1], e.max_abs[2]);
  out["mae_avg"] = e.mae_avg;
  out["psnr_db"] = e.psnr_db;
  out["pixels"] = e.pixels;
  out["error"] = image_array(std::move(error));
  out["heatmap"] = image_array(std::move(heat));
  return out;
}

}  // namespace

void bind_eval(py::module_& m) {
  m.def("image_error", &image_error_py, py::arg("approx"), py::arg("reference"), py::arg("mask") = py::none(),
        py::arg("heatmap_max") = kErrorHeatmapMax,
        "Error of `approx` against `reference` (both H×W×C float32 linear RGB, C ≥ 3; extra channels are "
        "ignored) as every proxima command reports it: values clamped to [0, 1], sRGB-encoded and scaled "
        "to 0–255. mask: optional H×W array, nonzero = compare. Returns a dict: mae and max_abs (per "
        "channel R, G, B, 0–255), mae_avg (mean of the three), psnr_db (+inf when equal), pixels (compared), "
        "error (H×W float32 per-pixel mean absolute error, 0–255, 0 outside the mask), heatmap (H×W×3 "
        "float32 linear RGB: black → purple → orange → yellow from 0 to heatmap_max, grey outside the mask).");
  m.def(
      "read_exr",
      [](const std::string& path) {
        ImageF image;
        {
          py::gil_scoped_release release;
          image = read_exr(path);
        }
        return image_array(std::move(image));
      },
      py::arg("path"),
      "Reads a float EXR (1–4 channels) as H×W (one channel) or H×W×C float32, row 0 on top, values as "
      "stored (the renders' .exr files are linear RGB).");
  m.def(
      "write_exr",
      [](const std::string& path, py::handle image_obj) {
        const ImageF image = checked_image(image_obj, "image", 1);
        py::gil_scoped_release release;
        write_exr(path, image);
      },
      py::arg("path"), py::arg("image"),
      "Writes an H×W or H×W×C (C ≤ 4) float32 array as a 32-bit float EXR (channels Y, or R G B (A)); "
      "written to a temporary file and renamed.");
  m.def(
      "read_image",
      [](const std::string& path) {
        ImageF image;
        {
          py::gil_scoped_release release;
          image = read_image_linear(path, 3);
        }
        return image_array(std::move(image));
      },
      py::arg("path"), "Reads a PNG or JPEG as H×W×3 float32 linear RGB (sRGB decoded).");
  m.def(
      "write_png",
      [](const std::string& path, py::handle image_obj) {
        const ImageF image = checked_image(image_obj, "image", 1);
        if (image.channels() == 2) fail_input("image: expected 1, 3 or 4 channels, got " + describe(image_obj));
        py::gil_scoped_release release;
        write_png_linear(path, image);
      },
      py::arg("path"), py::arg("image"),
      "Writes an H×W or H×W×C (C = 1, 3, 4) float32 linear array in [0, 1] as an 8-bit sRGB PNG.");
}

}  // namespace proxima::python
