// Winged-pair files (`proxima visibility --load`): load_winged_pair, then what the command
// does with the structure — beam tracing a small visibility map from a few viewpoints and
// rasterizing it. A loaded structure must be safe to traverse: every derived index in
// range, every face loop and edge spin closed, and tracing finishes or reports an
// InputError.
#include "fuzz_util.h"
#include "proxima/core/camera.h"
#include "proxima/visibility/visibility_map.h"
#include "proxima/visibility/winged_pair_io.h"

namespace {

using namespace proxima;
using namespace proxima::visibility;

bool finite(const dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void check_winged_pair(const WingedPair& wp) {
  const size_t nv = wp.vertices.size(), ne = wp.edges.size(), nf = wp.faces.size(), nc = wp.cells.size(),
               np = wp.pairs.size();
  FUZZ_CHECK(wp.scale > 0.0 && std::isfinite(wp.scale));
  FUZZ_CHECK(wp.loop_offset.size() == nf + 1 && wp.loop_offset.back() == wp.loop_vertex.size());
  FUZZ_CHECK(wp.loop_edge.size() == wp.loop_vertex.size());
  for (uint32_t v : wp.loop_vertex) FUZZ_CHECK(v < nv);
  for (uint32_t e : wp.loop_edge) FUZZ_CHECK(e < ne);
  FUZZ_CHECK(wp.cell_face_offset.size() == nc + 1 && wp.cell_face_offset.back() == wp.cell_face.size());
  for (uint32_t f : wp.cell_face) FUZZ_CHECK(f < nf);
  for (const Vertex& v : wp.vertices) FUZZ_CHECK(finite(v.position));
  for (const Face& f : wp.faces) {
    FUZZ_CHECK(f.pair < np && (f.polygon == kNone || f.polygon < wp.polygon_count));
    FUZZ_CHECK(std::isfinite(f.plane.offset) && finite(f.plane.normal));
  }
  for (const Pair& p : wp.pairs)
    FUZZ_CHECK(p.face < nf && p.edge < ne && p.clock[0] < np && p.clock[1] < np && p.spin[0] < np && p.spin[1] < np);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".wp");
  fuzz::expect_input_errors_only([&] {
    const WingedPair wp = load_winged_pair(path);
    check_winged_pair(wp);
    if (wp.vertices.empty()) return;
    // Viewpoints: the center of the vertex bounds and two points between it and a corner.
    dvec3 lo = wp.vertices[0].position, hi = lo;
    for (const Vertex& v : wp.vertices) {
      lo = glm::min(lo, v.position);
      hi = glm::max(hi, v.position);
    }
    const dvec3 mid = 0.5 * (lo + hi);
    for (double t : {0.0, 0.3, 0.7}) {
      const vec3 eye(mid + t * (hi - mid));
      Camera cam = look_at(eye, eye + vec3(0.3f, -0.1f, -1.0f), vec3(0, 1, 0), 60.0f, 16, 12, 1e-3f, 1e3f);
      try {
        const VisibilityMap map = trace_visibility_map(wp, cam);
        for (const MapRegion& r : map.regions) FUZZ_CHECK(r.polygon == kNone || r.polygon < wp.polygon_count);
        const ImageU32 ids = rasterize_map(map);
        FUZZ_CHECK(ids.width() == 16 && ids.height() == 12);
        (void)map_edge_mask(map);
      } catch (const InputError&) {  // camera outside the outer box, or not a valid camera
      }
    }
  });
  return 0;
}
