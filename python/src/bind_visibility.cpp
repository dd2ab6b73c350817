// Exact visibility maps (visibility/visibility_map.h, docs/visibility.md): the winged pair
// of a scene built once (or loaded), then a map per camera — regions as polygon arrays,
// the label image, silhouette edges — with its self-check against Embree.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "bindings.h"
#include "proxima/core/camera.h"
#include "proxima/core/limits.h"
#include "proxima/core/range_check.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/map_check.h"
#include "proxima/visibility/visibility_map.h"
#include "proxima/visibility/winged_pair_io.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

using namespace proxima::visibility;

int32_t id_or_minus_one(uint32_t id) { return id == kNone ? -1 : int32_t(id); }

// The winged pair of a scene's polygons and the Embree rays of its welded geometry (what the
// maps are exact for), built once.
class VisibilityMaps {
 public:
  VisibilityMaps(const SceneHandle& handle, const std::optional<std::filesystem::path>& load) {
    if (load && load->empty()) fail_input("load: must not be empty (None builds the winged pair)");
    py::gil_scoped_release release;
    const auto lock = handle.read_lock();
    model_ = extract_polygons(handle.scene());
    if (load) {
      wp_ = load_winged_pair(*load);
      if (wp_.polygon_count != model_.polygons.size())
        fail_input("load: " + load->string() + " was built for " + std::to_string(wp_.polygon_count) +
                   " polygons, the scene has " + std::to_string(model_.polygons.size()));
    } else {
      wp_ = build_winged_pair(model_, {}, &bsp_);
    }
    welded_ = welded_scene(handle.scene(), model_);
    rays_ = std::make_unique<RayScene>(welded_);
  }

  py::dict trace(const Camera& camera, bool check, int check_rays) const {
    validate_camera(camera, "camera");
    check_image_budget("camera", uint64_t(camera.width), uint64_t(camera.height), 4);
    require_in_range(check_rays, 1, 1000000, "check_rays");
    VisibilityMap map;
    ImageU32 labels;
    MapCheck result;
    {
      py::gil_scoped_release release;
      map = trace_visibility_map(wp_, camera);
      labels = rasterize_map(map);
      if (check) {
        MapCheckOptions options;
        options.rays = check_rays;
        result = check_visibility_map(map, model_, *rays_, camera, options);
      }
    }
    py::dict out = regions_dict(map);
    out["labels"] = id_image_array(std::move(labels));
    out["edges"] = edges_array(map, false);
    out["silhouette_edges"] = edges_array(map, true);
    out["stats"] = stats_dict(map.stats);
    if (check) out["check"] = check_dict(result);
    return out;
  }

  void save(const std::filesystem::path& path) const { save_winged_pair(path, wp_); }

  py::dict build_stats() const {
    return named({{"polygons", model_.polygons.size()}, {"cells", wp_.cells.size()},
        {"faces", wp_.faces.size()}, {"edges", wp_.edges.size()}, {"vertices", wp_.vertices.size()},
        {"build_ms", bsp_.build_ms}, {"unplaced_fragments", bsp_.unplaced_fragments},
        {"rejected_planes", bsp_.rejected_planes}});
  }

  py::array triangle_polygon() const {
    std::vector<uint32_t> ids = model_.triangle_polygon;
    const auto n = py::ssize_t(ids.size());
    return buffer_array<int32_t>(std::move(ids), {n});
  }

  py::array polygon_object() const {
    std::vector<int32_t> ids;
    for (const InputPolygon& p : model_.polygons) ids.push_back(int32_t(p.object));
    const auto n = py::ssize_t(ids.size());
    return buffer_array<int32_t>(std::move(ids), {n});
  }

 private:
  static py::dict regions_dict(const VisibilityMap& map) {
    py::list polygons;
    std::vector<int32_t> polygon, merged;
    for (const MapRegion& r : map.regions) {
      std::vector<dvec2> vertices = r.vertices;
      const auto n = py::ssize_t(vertices.size());
      polygons.append(buffer_array<double>(std::move(vertices), {n, 2}));
      polygon.push_back(id_or_minus_one(r.polygon));
      merged.push_back(id_or_minus_one(r.merged));
    }
    const auto count = py::ssize_t(polygon.size());
    return named({{"regions", polygons},
        {"region_polygon", buffer_array<int32_t>(std::move(polygon), {count})},
        {"region_merged", buffer_array<int32_t>(std::move(merged), {count})}});
  }

  // E×2×2 float64: edge e runs from [e, 0] to [e, 1] (pixel coordinates).
  static py::array edges_array(const VisibilityMap& map, bool silhouettes_only) {
    std::vector<dvec2> ends;
    for (const MapEdge& e : map.edges) {
      if (silhouettes_only && !e.silhouette) continue;
      ends.push_back(map.vertices[e.vertex[0]]);
      ends.push_back(map.vertices[e.vertex[1]]);
    }
    const auto n = py::ssize_t(ends.size() / 2);
    return buffer_array<double>(std::move(ends), {n, 2, 2});
  }

  static py::dict stats_dict(const MapStats& s) {
    return named({{"beams", s.beams}, {"cells_visited", s.cells_visited}, {"faces_culled", s.faces_culled},
        {"escaped", s.escaped}, {"regions", s.regions}, {"merged_regions", s.merged_regions},
        {"visible_polygons", s.visible_polygons}, {"silhouette_edges", s.silhouette_edges}, {"ms", s.ms}});
  }

  static py::dict check_dict(const MapCheck& c) {
    return named({{"passed", c.pass}, {"reason", c.reason}, {"area_ratio", c.area_ratio},
        {"samples", c.samples}, {"mismatches", c.mismatches}, {"coplanar_ties", c.coplanar_ties},
        {"ms", c.ms}});
  }

  ModelPolygons model_;
  WingedPair wp_;
  BspStats bsp_;
  Scene welded_;
  std::unique_ptr<RayScene> rays_;
};

}  // namespace

void bind_visibility(py::module_& m) {
  static_assert(sizeof(dvec2) == 2 * sizeof(double));
  py::class_<VisibilityMaps>(
      m, "VisibilityMaps",
      "Exact visibility maps (Funkhouser's beam tracing, docs/visibility.md) of a scene: its triangles merged "
      "into convex polygons, the spatial subdivision (BSP → winged pair) built once at construction (GIL "
      "released) or read from a file saved by save() or `proxima visibility --save` (load=path), then "
      "trace(camera) for any camera inside the scene's outer box. Polygon ids: triangle_polygon maps "
      "triangle ids onto them.")
      .def(py::init([](const SceneHandle& scene, const std::optional<std::filesystem::path>& load) {
             return std::make_unique<VisibilityMaps>(scene, load);
           }),
           py::arg("scene"), py::kw_only(), py::arg("load") = py::none())
      .def("trace", &VisibilityMaps::trace, py::arg("camera"), py::kw_only(), py::arg("check") = true,
           py::arg("check_rays") = MapCheckOptions{}.rays,
           "The visibility map of `camera` (near/far ignored: exact at every depth), in pixel coordinates (x "
           "right, y down, pixel centers at +0.5, the map covering [0, W] × [0, H]). GIL released. Returns a "
           "dict: regions (list of K_i×2 float64 arrays, convex polygons with positive shoelace area), "
           "region_polygon (R int32, the polygon each region shows, −1 background), region_merged (R int32, "
           "merged-region id: contiguous regions of one polygon), labels (H×W int32, the polygon at each pixel "
           "center, −1 background), edges (E×2×2 float64, every map edge as its two end points), "
           "silhouette_edges (S×2×2 float64, the occluding contours among them), stats (beams, cells_visited, "
           "faces_culled, escaped, regions, merged_regions, visible_polygons, silhouette_edges, ms), and with "
           "check the self-check against check_rays Embree rays: check (passed, reason, area_ratio, samples, "
           "mismatches, coplanar_ties, ms). ValueError when the camera is outside the outer box.")
      .def("save", &VisibilityMaps::save, py::arg("path"),
           "Writes the winged pair to `path` (`proxima visibility --load` and VisibilityMaps(load=…) read it).")
      .def_property_readonly("build_stats", &VisibilityMaps::build_stats,
                             "The winged pair (the paper's Table 1): polygons, cells, faces, edges, vertices, "
                             "build_ms, unplaced_fragments, rejected_planes (0 for a loaded one).")
      .def_property_readonly("triangle_polygon", &VisibilityMaps::triangle_polygon,
                             "Per scene triangle: the polygon id it was merged into (N int32).")
      .def_property_readonly("polygon_object", &VisibilityMaps::polygon_object,
                             "Per polygon: the scene object id it belongs to (P int32).");
}

}  // namespace proxima::python
