// Hybrid geometry- and image-based rendering (gibr/gibr_model.h, gibr/novel_view.h,
// docs/gibr.md): the model built once — from photographs given as arrays with their cameras,
// or from synthetic ones rendered along the scene's walk path — and novel views rendered
// from it for any camera.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "proxima/core/camera.h"
#include "proxima/core/limits.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/gibr/novel_view.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

// The photographs and cameras of Python: a list of H×W×3 float32 arrays (linear RGB) and a
// list of Camera of the same length, each camera the size of its photograph.
gibr::GivenPhotos given_photos(const py::handle& photos, const py::handle& cameras) {
  if (cameras.is_none()) fail_input("cameras: required with photographs given as arrays");
  gibr::GivenPhotos given;
  try {
    given.cameras = cameras.cast<std::vector<Camera>>();
  } catch (const py::cast_error&) {
    fail_input("cameras: expected a list of Camera, got " + describe(cameras));
  }
  for (const py::handle photo : photos) {
    ImageF image = checked_image(photo, "photos", 3);
    check_finite(image.data().data(), image.data().size(), "photos");
    given.images.push_back(std::move(image));
  }
  return given;
}

class GibrModel {
 public:
  GibrModel(const SceneHandle& handle, const py::object& photos, const py::object& cameras,
            const gibr::GibrModelOptions& options)
      : item_buffer_(options.item_buffer), supersample_(options.supersample) {
    const bool given = !photos.is_none() && !py::isinstance<py::int_>(photos);
    gibr::GibrModelOptions o = options;
    gibr::GivenPhotos photographs;
    if (given) {
      if (!py::isinstance<py::sequence>(photos)) fail_input("photos: expected a count or a list of arrays");
      photographs = given_photos(photos, cameras);
    } else {
      if (!cameras.is_none()) fail_input("cameras: only with photographs given as arrays");
      if (!photos.is_none()) o.photos = photos.cast<int>();
    }
    py::gil_scoped_release release;
    const auto lock = handle.read_lock();
    model_ = given ? gibr::build_gibr_model(handle.scene(), o, std::move(photographs))
                   : gibr::build_gibr_model(handle.scene(), o);
  }

  py::dict render(const Camera& camera, int k, int hole_radius, int supersample, const std::string& mapping) const {
    if (mapping != "vismap" && mapping != "itembuffer")
      fail_input("mapping: expected 'vismap' or 'itembuffer', got '" + mapping + "'");
    if (mapping == "itembuffer" && !item_buffer_) fail_input("mapping: the model was built without item_buffer");
    gibr::NovelViewOptions o;
    o.k = k;
    o.hole_radius = hole_radius;
    o.supersample = supersample > 0 ? supersample : supersample_;
    if (k < 1 || k > 64) fail_input("k: must be in 1..64");
    if (hole_radius < 0 || hole_radius > 4096) fail_input("hole_radius: must be in 0..4096");
    if (o.supersample > 8) fail_input("supersample: must be in 0..8");
    validate_camera(camera, "camera");
    check_image_budget("camera", uint64_t(camera.width) * uint64_t(o.supersample),
                       uint64_t(camera.height) * uint64_t(o.supersample), 12);
    gibr::NovelView view;
    {
      py::gil_scoped_release release;
      view = gibr::render_novel_view(model_.scene, model_.model, mapping == "vismap" ? model_.maps : model_.item_maps,
                                     camera, o);
    }
    py::dict stats = named({{"covered", view.covered}, {"holes", view.holes},
        {"holes_filled", view.holes_filled}, {"raster_ms", view.raster_ms}, {"blend_ms", view.blend_ms}});
    return named({{"color", image_array(std::move(view.color))},
        {"unseen", image_array<bool>(std::move(view.unseen))}, {"stats", stats}});
  }

  const std::vector<Camera>& cameras() const { return model_.cameras; }

  py::list photos() const {
    py::list out;
    for (const ImageF& photo : model_.photos) out.append(image_copy_array(photo));
    return out;
  }

  py::dict stats() const {
    const gibr::GibrModelStats& s = model_.stats;
    const gibr::RadianceStats& r = model_.maps.stats;
    return named({{"photos", model_.cameras.size()}, {"polygons", model_.model.polygons.size()},
        {"texel_m", model_.texel}, {"layers", r.layers}, {"samples", r.samples},
        {"samples_extrapolated", r.samples_extrapolated}, {"samples_unmixed", r.samples_unmixed},
        {"texels", r.texels}, {"texels_covered", r.texels_covered}, {"pixels_mapped", r.pixels_mapped},
        {"photos_ms", s.photos_ms}, {"bsp_ms", s.bsp.build_ms}, {"vismap_ms", s.vismap_ms},
        {"itembuffer_ms", s.itembuffer_ms}, {"silhouette_edges_avg", s.silhouette_edges_avg},
        {"maps_failed_selfcheck", s.maps_failed_selfcheck}, {"selfcheck_failures", s.selfcheck_failures},
        {"total_ms", s.total_ms}});
  }

  float far_plane() const { return float(model_.far); }

 private:
  gibr::GibrModel model_;
  bool item_buffer_ = false;
  int supersample_ = 1;
};

}  // namespace

void bind_gibr(py::module_& m) {
  const gibr::GibrModelOptions d;
  const gibr::NovelViewOptions nv;
  py::class_<GibrModel>(
      m, "GibrModel",
      "Hybrid geometry- and image-based rendering (Funkhouser's phases 1–3, docs/gibr.md), built once at "
      "construction (GIL released): the scene's triangles merged into polygons, the winged pair, a visibility "
      "map per photograph and the radiance maps of the photographs' colors on the polygons' texel grids. "
      "photos: a list of H×W×3 float32 arrays (linear RGB) taken by `cameras` (a list of Camera, each of its "
      "photograph's size), or a count of synthetic photographs rendered from seeded poses along the scene's "
      "first camera path at photo_width × photo_height (default: photos=100, as `proxima gibr`). Options as "
      "`proxima gibr`'s flags: texel (m; 0 = the scene's default), period (m, texture repeat of the synthetic "
      "photo scene; 0 = default), supersample (k×k samples per photograph pixel, and the novel views' default), "
      "exclude_boundaries, whole_pixels, unmix, item_buffer (also build the item-buffer baseline's maps), "
      "seed. The scene needs a camera path (the photo scene's far plane and defaults come from it).")
      .def(py::init([](const SceneHandle& scene, const py::object& photos, const py::object& cameras,
                       int photo_width, int photo_height, double texel, double period, int supersample,
                       bool exclude_boundaries, bool whole_pixels, bool unmix, bool item_buffer, uint64_t seed) {
             gibr::GibrModelOptions o;
             o.photo_width = photo_width;
             o.photo_height = photo_height;
             o.texel = texel;
             o.period = period;
             o.supersample = supersample;
             o.exclude_boundaries = exclude_boundaries;
             o.whole_pixels = whole_pixels;
             o.unmix = unmix;
             o.item_buffer = item_buffer;
             o.seed = seed;
             return std::make_unique<GibrModel>(scene, photos, cameras, o);
           }),
           py::arg("scene"), py::arg("photos") = py::none(), py::arg("cameras") = py::none(), py::kw_only(),
           py::arg("photo_width") = d.photo_width, py::arg("photo_height") = d.photo_height,
           py::arg("texel") = d.texel, py::arg("period") = d.period, py::arg("supersample") = d.supersample,
           py::arg("exclude_boundaries") = d.exclude_boundaries, py::arg("whole_pixels") = d.whole_pixels,
           py::arg("unmix") = d.unmix, py::arg("item_buffer") = d.item_buffer, py::arg("seed") = d.seed)
      .def("render", &GibrModel::render, py::arg("camera"), py::kw_only(), py::arg("k") = nv.k,
           py::arg("hole_radius") = nv.hole_radius, py::arg("supersample") = 0, py::arg("mapping") = "vismap",
           "A novel view from `camera` (phase 4): the model rasterized, each pixel blending the k photographs "
           "whose directions are closest to the view's; holes filled from the nearest texel within hole_radius "
           "texels. supersample: s×s samples per pixel (0 = the model's). mapping: 'vismap' or 'itembuffer' "
           "(needs item_buffer=True). GIL released. Returns a dict: color (H×W×3 float32 linear RGB, black "
           "where nothing is rasterized), unseen (H×W bool, no photograph saw the pixel's surface), stats "
           "(covered, holes, holes_filled: pixels; raster_ms, blend_ms).")
      .def_property_readonly("cameras", &GibrModel::cameras, "The photographs' cameras (list of Camera).")
      .def_property_readonly("photos", &GibrModel::photos,
                             "The photographs, a list of H×W×3 float32 arrays (linear RGB; copies).")
      .def_property_readonly("stats", &GibrModel::stats,
                             "The model: photos, polygons, texel_m, the visibility-map radiance maps' layers, "
                             "samples, samples_extrapolated, samples_unmixed, texels, texels_covered, "
                             "pixels_mapped, and the build's photos_ms, bsp_ms, vismap_ms, itembuffer_ms, "
                             "silhouette_edges_avg, maps_failed_selfcheck, selfcheck_failures (one line each), "
                             "total_ms.")
      .def_property_readonly("far", &GibrModel::far_plane, "The far plane of every camera of the model (m).");
}

}  // namespace proxima::python
