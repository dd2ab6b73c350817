// Phase 3 of Funkhouser's GIBR system (section 2): "the visibility maps are used to map
// regions of the calibrated images onto 3D polygons to create a set of radiance maps".
// The paper's point (section 1, Figure 1) is that pixels covering several disjoint surfaces
// — along silhouette edges — must not be mapped onto any single surface; the visibility
// map finds them, a z-buffer item buffer (Debevec et al.'s visibility) does not.
#include "proxima/gibr/radiance_map.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/image_rgb.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"

namespace proxima::gibr {

using namespace proxima::visibility;

uint32_t pack_srgb8(const vec3& linear) {
  uint32_t out = 0xFF000000u;
  for (int c = 0; c < 3; ++c) {
    const float s = linear_to_srgb(std::clamp(linear[c], 0.0f, 1.0f));
    out |= uint32_t(std::lround(s * 255.0f)) << (8 * c);
  }
  return out;
}

namespace {
struct SrgbTable {
  float v[256];
  SrgbTable() {
    for (int i = 0; i < 256; ++i) v[i] = srgb_to_linear(float(i) / 255.0f);
  }
};
const SrgbTable kSrgb;
}  // namespace

vec3 unpack_srgb8(uint32_t rgba) {
  return {kSrgb.v[rgba & 0xFF], kSrgb.v[(rgba >> 8) & 0xFF], kSrgb.v[(rgba >> 16) & 0xFF]};
}

std::vector<TexelGrid> make_texel_grids(const ModelPolygons& model, double texel) {
  if (!(texel > 0.0) || !std::isfinite(texel)) fail_input("--texel: must be a positive size in meters");
  std::vector<TexelGrid> grids;
  grids.reserve(model.polygons.size());
  for (const InputPolygon& p : model.polygons) {
    TexelGrid g;
    g.texel = texel;
    g.u = glm::normalize(p.vertices[1] - p.vertices[0]);
    g.v = glm::normalize(glm::cross(p.plane.normal, g.u));
    dvec2 lo(INFINITY), hi(-INFINITY);
    for (const dvec3& q : p.vertices) {
      const dvec2 c(glm::dot(q - p.vertices[0], g.u), glm::dot(q - p.vertices[0], g.v));
      lo = glm::min(lo, c);
      hi = glm::max(hi, c);
    }
    lo -= dvec2(texel);
    hi += dvec2(texel);
    g.origin = p.vertices[0] + lo.x * g.u + lo.y * g.v;
    const double w = std::ceil((hi.x - lo.x) / texel), h = std::ceil((hi.y - lo.y) / texel);
    if (w * h > double(1 << 26)) fail_input("--texel: " + std::to_string(texel) + " m gives a polygon of " +
                                            std::to_string(w * h) + " texels (at most 2^26)");
    g.width = int(w);
    g.height = int(h);
    grids.push_back(g);
  }
  return grids;
}

ImageU8 silhouette_pixel_mask(const VisibilityMap& map, double radius) {
  VisibilityMap sil;
  sil.width = map.width;
  sil.height = map.height;
  sil.vertices = map.vertices;
  sil.regions = map.regions;
  for (const MapEdge& e : map.edges)
    if (e.silhouette) sil.edges.push_back(e);
  return map_edge_mask(sil, radius);
}

namespace {

// Pixels whose square touches a silhouette edge (or any edge between different polygons):
// a pixel square touches a segment only if the segment passes within √2/2 of its center.
ImageU8 touched_mask(const VisibilityMap& m, bool exclude_all_boundaries) {
  const double radius = std::sqrt(0.5) + 1e-9;
  return exclude_all_boundaries ? map_edge_mask(m, radius) : silhouette_pixel_mask(m, radius);
}

// The map scaled by `factor`: its pixel centers are the cell centers of a factor × factor
// grid in each pixel of the original.
VisibilityMap scaled_map(const VisibilityMap& map, int factor) {
  VisibilityMap fine = map;
  fine.width *= factor;
  fine.height *= factor;
  for (dvec2& v : fine.vertices) v *= double(factor);
  for (MapRegion& r : fine.regions)
    for (dvec2& v : r.vertices) v *= double(factor);
  return fine;
}


}  // namespace

ImageU32 vismap_pixel_polygons(const VisibilityMap& map, bool exclude_all_boundaries, bool subpixel) {
  const ImageU32 centers = rasterize_map(map);
  const ImageU8 touched = touched_mask(map, exclude_all_boundaries);
  ImageU32 labels(map.width, map.height, subpixel ? kRecordChannels : 1, kNone);
  if (subpixel)
    for (int y = 0; y < map.height; ++y)
      for (int x = 0; x < map.width; ++x)
        for (int c = 3; c < kRecordChannels; ++c) labels.at(x, y, c) = 0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      if (!touched.at(x, y)) labels.at(x, y) = centers.at(x, y);
  if (!subpixel) return labels;
  // The same test on the map scaled by kSubCells: which sub-cells of a touched pixel lie
  // wholly inside one polygon's regions.
  const VisibilityMap fine = scaled_map(map, kSubCells);
  const ImageU32 fine_centers = rasterize_map(fine);
  const ImageU8 fine_touched = touched_mask(fine, exclude_all_boundaries);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      if (!touched.at(x, y)) continue;
      for (int s = 0; s < kSubCells * kSubCells; ++s) {
        const int fx = x * kSubCells + s % kSubCells, fy = y * kSubCells + s / kSubCells;
        const uint32_t p = fine_centers.at(fx, fy);
        if (p == kNone || fine_touched.at(fx, fy)) continue;
        // Up to two polygons per pixel (the two sides of a silhouette); a third is dropped.
        for (int k = 0; k < 2; ++k) {
          uint32_t& q = labels.at(x, y, 1 + k);
          if (q == kNone) q = p;
          if (q != p) continue;
          labels.at(x, y, 3 + k * kMaskWords + s / 32) |= 1u << (s % 32);
          break;
        }
      }
    }
  return labels;
}

ImageU32 unmix_silhouette_pixels(const VisibilityMap& map, const ImageU32& labels, const ImageF& photo, int samples,
                                 bool exclude_all_boundaries, bool two_pass) {
  const int W = map.width, H = map.height;
  const int L = labels.channels();
  if (labels.width() != W || labels.height() != H || (L != 1 && L != kRecordChannels) || photo.width() != W ||
      photo.height() != H || photo.channels() < 3)
    fail_input("unmixing: the labels (1 channel or a sub-pixel record) and photograph must have the map's size");
  if (samples < 1 || samples > 8) fail_input("unmixing: samples per pixel side must be in 1..8");
  UnmixInputs in;
  in.samples = samples;
  in.centers = rasterize_map(map);
  in.touched = touched_mask(map, exclude_all_boundaries);
  in.on_any_edge = touched_mask(map, true);
  in.fine = rasterize_map(scaled_map(map, samples));
  return unmix_pixels(labels, photo, in, two_pass);
}

ImageU32 unmix_pixels(const ImageU32& labels, const ImageF& photo, const UnmixInputs& in, bool two_pass) {
  const int W = labels.width(), H = labels.height();
  const int L = labels.channels();
  const int samples = in.samples;
  if (photo.width() != W || photo.height() != H || photo.channels() < 3 || in.centers.width() != W ||
      in.centers.height() != H || in.touched.width() != W || in.touched.height() != H || in.on_any_edge.width() != W ||
      in.on_any_edge.height() != H || samples < 1 || samples > 8 || in.fine.width() != W * samples ||
      in.fine.height() != H * samples)
    fail_input("unmixing: the labels, photograph and the map's images must have one size");
  ImageU32 out(W, H, L + 2, kNone);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      for (int c = 0; c < L; ++c) out.at(x, y, c) = labels.at(x, y, c);
      out.at(x, y, L + 1) = 0;
    }
  const ImageU32& centers = in.centers;
  const ImageU8& touched = in.touched;
  // The other sides' colors come from pixels wholly inside one polygon's regions (touching
  // no edge between different polygons: a pixel on a crease is a mix too).
  const ImageU8& on_any_edge = in.on_any_edge;
  // The polygon each of the photograph's s × s samples sees.
  const ImageU32& fine = in.fine;
  const int n = samples * samples;
  std::vector<std::pair<uint32_t, int>> sides;  // polygon (kNone = background), samples
  // Pixel (x, y) unmixed for its majority polygon: false when it has none or another side's
  // color is unknown. A side's color is the nearest pixel within 2 px wholly on it — or, with
  // `second` (thin occluders: no pixel wholly on them), the nearest pixel unmixed for it in the
  // first pass (`first`: that pass's result; its colors only, so no chains of unmixing).
  auto unmix_pixel = [&](int x, int y, const ImageU32* first, uint32_t& polygon, uint32_t& packed) {
    sides.clear();
    for (int s = 0; s < n; ++s) {
      const uint32_t q = fine.at(x * samples + s % samples, y * samples + s / samples);
      auto it = std::find_if(sides.begin(), sides.end(), [&](const auto& e) { return e.first == q; });
      if (it == sides.end()) sides.push_back({q, 1});
      else ++it->second;
    }
    // P: the first side (in sample order) with at least half the samples; not the background.
    const auto P = std::find_if(sides.begin(), sides.end(), [&](const auto& e) { return 2 * e.second >= n; });
    if (P == sides.end() || P->first == kNone) return false;
    vec3 c = rgb_at(photo, x, y);
    for (const auto& [q, count] : sides) {
      if (q == P->first) continue;
      // The other side's color: the nearest pixel within 2 px wholly on it (first in row order).
      double best = 4.0 + 1e-9;
      vec3 cq(0.0f);
      for (int yy = std::max(0, y - 2); yy <= std::min(H - 1, y + 2); ++yy)
        for (int xx = std::max(0, x - 2); xx <= std::min(W - 1, x + 2); ++xx) {
          const double dd = double((xx - x) * (xx - x) + (yy - y) * (yy - y));
          if (dd >= best) continue;
          if (!on_any_edge.at(xx, yy) && centers.at(xx, yy) == q) best = dd, cq = rgb_at(photo, xx, yy);
        }
      if (best > 4.0 && first && q != kNone) {
        for (int yy = std::max(0, y - 2); yy <= std::min(H - 1, y + 2); ++yy)
          for (int xx = std::max(0, x - 2); xx <= std::min(W - 1, x + 2); ++xx) {
            const double dd = double((xx - x) * (xx - x) + (yy - y) * (yy - y));
            if (dd < best && dd > 0.0 && first->at(xx, yy, L) == q) best = dd, cq = unpack_srgb8(first->at(xx, yy, L + 1));
          }
      }
      if (best > 4.0) return false;
      c -= (float(count) / float(n)) * cq;
    }
    polygon = P->first;
    packed = pack_srgb8(c * (float(n) / float(P->second)));  // pack_srgb8 clamps to [0, 1]
    return true;
  };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (touched.at(x, y)) unmix_pixel(x, y, nullptr, out.at(x, y, L), out.at(x, y, L + 1));
  if (!two_pass) return out;
  const ImageU32 first = out;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (touched.at(x, y) && first.at(x, y, L) == kNone) unmix_pixel(x, y, &first, out.at(x, y, L), out.at(x, y, L + 1));
  return out;
}

ImageU32 itembuffer_pixel_polygons(const Scene& scene, const ModelPolygons& model, const Camera& camera) {
  RasterOptions ro;
  ro.outputs = kRasterTriangle | kRasterDepth;
  RasterImages img = rasterize(scene, camera, ro);
  ImageU32 out(camera.width, camera.height, 1, kNone);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const uint32_t t = img.triangle.at(x, y);
      if (t != kNoTriangle) out.at(x, y) = model.triangle_polygon[t];
    }
  return out;
}

namespace {

// The visibility map's regions of a polygon meeting each pixel that may show more than one
// polygon — not mapped as a whole (label kNone: touching a silhouette,
// or background) or beside a pixel with another label (a crease between polygons: the
// pixel is mapped onto its center's polygon, another one may still cover part of it):
// in region order (compressed rows: pixel → [first[i], first[i + 1])).
struct PixelRegions {
  std::vector<uint32_t> first, region;
};

ImageU8 boundary_pixels(const ImageU32& labels) {
  const int W = labels.width(), H = labels.height();
  ImageU8 out(W, H, 1, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const uint32_t c = labels.at(x, y);
      bool b = c == kNone;
      for (int yy = std::max(0, y - 1); !b && yy <= std::min(H - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); !b && xx <= std::min(W - 1, x + 1); ++xx) b = labels.at(xx, yy) != c;
      out.at(x, y) = b;
    }
  return out;
}

// The x extent of the convex region R within the row band [y, y + 1] (empty: lo > hi):
// the pixels of the row whose closed squares meet R are floor(lo) … floor(hi).
dvec2 row_extent(const MapRegion& R, int y) {
  const double y0 = y, y1 = y + 1.0;
  dvec2 ext(INFINITY, -INFINITY);
  const size_t n = R.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    const dvec2 a = R.vertices[k], b = R.vertices[(k + 1) % n];
    // The part of edge a → b inside the band.
    double ta = 0.0, tb = 1.0;
    if (a.y != b.y) {
      const double t0 = (y0 - a.y) / (b.y - a.y), t1 = (y1 - a.y) / (b.y - a.y);
      ta = std::max(ta, std::min(t0, t1));
      tb = std::min(tb, std::max(t0, t1));
    } else if (a.y < y0 || a.y > y1) {
      continue;
    }
    if (ta > tb) continue;
    for (double t : {ta, tb}) {
      const double x = a.x + t * (b.x - a.x);
      ext = dvec2(std::min(ext.x, x), std::max(ext.y, x));
    }
  }
  return ext;
}

PixelRegions pixel_regions(const VisibilityMap& map, const ImageU8& boundary) {
  const int W = map.width, H = map.height;
  PixelRegions out;
  out.first.assign(size_t(W) * size_t(H) + 1, 0);
  // Two passes over the regions' boxes: count per pixel, then fill.
  auto for_each = [&](auto&& f) {
    for (uint32_t r = 0; r < map.regions.size(); ++r) {
      const MapRegion& R = map.regions[r];
      if (R.polygon == kNone || R.vertices.empty()) continue;
      dvec2 lo(INFINITY), hi(-INFINITY);
      for (const dvec2& v : R.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
      const int y0 = std::max(0, int(std::floor(lo.y))), y1 = std::min(H - 1, int(std::floor(hi.y)));
      for (int y = y0; y <= y1; ++y) {
        const dvec2 e = row_extent(R, y);
        if (!(e.x <= e.y)) continue;
        const int x0 = std::max(0, int(std::floor(e.x))), x1 = std::min(W - 1, int(std::floor(e.y)));
        for (int x = x0; x <= x1; ++x)
          if (boundary.at(x, y)) f(size_t(y) * size_t(W) + size_t(x), r);
      }
    }
  };
  for_each([&](size_t i, uint32_t) { ++out.first[i + 1]; });
  for (size_t i = 1; i < out.first.size(); ++i) out.first[i] += out.first[i - 1];
  out.region.resize(out.first.back());
  std::vector<uint32_t> next(out.first.begin(), out.first.end() - 1);
  for_each([&](size_t i, uint32_t r) { out.region[next[i]++] = r; });
  return out;
}

// The convex polygon `poly` clipped to the rectangle [lo, hi] (Sutherland–Hodgman).
void clip_to_rect(std::span<const dvec2> poly, const dvec2& lo, const dvec2& hi, std::vector<dvec2>& out) {
  out.assign(poly.begin(), poly.end());
  std::vector<dvec2> in;
  for (int side = 0; side < 4; ++side) {
    in.swap(out);
    out.clear();
    auto dist = [&](const dvec2& v) {
      switch (side) {
        case 0: return v.x - lo.x;
        case 1: return hi.x - v.x;
        case 2: return v.y - lo.y;
        default: return hi.y - v.y;
      }
    };
    for (size_t k = 0; k < in.size(); ++k) {
      const dvec2 a = in[k], b = in[(k + 1) % in.size()];
      const double da = dist(a), db = dist(b);
      if (da >= 0.0) out.push_back(a);
      if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (da / (da - db)) * (b - a));
    }
  }
}

// The same for the pixel square (x, y).
void clip_to_pixel(std::span<const dvec2> poly, int x, int y, std::vector<dvec2>& out) {
  clip_to_rect(poly, dvec2(x, y), dvec2(x + 1.0, y + 1.0), out);
}

// Distance (px) a point must keep from every edge of the region holding it to count as seen
// there: a margin for rounding between the map and the texel's projection, negligible next
// to the 8 × 8 sub-cell record's strip (≈ 0.09 px).
constexpr double kRegionMargin = 1e-3;

// Is q inside the convex region R (positive shoelace area: interior on the left of each edge)
// by at least kRegionMargin?
bool inside_region(const MapRegion& R, const dvec2& q) {
  const size_t n = R.vertices.size();
  for (size_t k = 0; k < n; ++k) {
    const dvec2 a = R.vertices[k], e = R.vertices[(k + 1) % n] - a, r = q - a;
    const double cross = e.x * r.y - e.y * r.x;  // |e| × the distance to the edge's line
    if (cross < 0.0 || cross * cross < kRegionMargin * kRegionMargin * (e.x * e.x + e.y * e.y)) {
      if (e.x == 0.0 && e.y == 0.0) continue;
      return false;
    }
  }
  return n >= 3;
}

PhotoLayers map_photo(const ModelPolygons& model, const std::vector<TexelGrid>& grids, uint32_t photo,
                      const Camera& cam, const ImageF& image, const ImageU32& labels, const VisibilityMap* vis_map,
                      const Lens& lens) {
  PhotoLayers out;
  const dvec3 eye(cam.position), R(camera_right(cam)), U(camera_up(cam)), F(camera_forward(cam));
  const double f = focal_length_px(cam), cx = 0.5 * cam.width, cy = 0.5 * cam.height;
  const int W = cam.width, H = cam.height;
  // Texel-coordinate bounds of each polygon's mapped pixels (their corners on its plane).
  std::vector<glm::dvec4> box(model.polygons.size(), glm::dvec4(INFINITY, INFINITY, -INFINITY, -INFINITY));
  std::vector<uint32_t> seen;
  std::vector<uint8_t> listed(model.polygons.size(), 0);
  // Exact-visible texels: from the map's regions when it is given (exact point test), else from
  // the sub-pixel record's sub-cells.
  const bool exact = vis_map != nullptr, sub = !exact && labels.channels() >= kRecordChannels;
  const int uc = unmix_channel(labels);
  const bool unmix = uc >= 0;
  const ImageU8 boundary = exact ? boundary_pixels(labels) : ImageU8();
  // Through a lens the labels are per pixel of the lens image and the map's regions are
  // looked up by the pinhole image point: every pixel of the map's grid gets its list.
  const bool pinhole = lens.pinhole();
  const PixelRegions candidates =
      !exact ? PixelRegions{} : pixel_regions(*vis_map, pinhole ? boundary : ImageU8(W, H, 1, 1));
  auto regions_at = [&](int x, int y) {
    const size_t i = size_t(y) * size_t(W) + size_t(x);
    return std::span<const uint32_t>(candidates.region.data() + candidates.first[i], candidates.first[i + 1] - candidates.first[i]);
  };
  auto any_bits = [&](int x, int y, int k) {
    for (int w = 0; w < kMaskWords; ++w)
      if (labels.at(x, y, 3 + k * kMaskWords + w)) return true;
    return false;
  };
  // Extends p's box by image points (their sightlines' hits on p's plane).
  auto add_points = [&](uint32_t p, std::span<const dvec2> points) {
    const Plane& pl = model.polygons[p].plane;
    const double d = pl.distance(eye);
    if (!listed[p]) seen.push_back(p), listed[p] = 1;
    for (const dvec2& q : points) {
      const double px = q.x, py = q.y;
      const dvec3 dir = F + ((px - cx) / f) * R - ((py - cy) / f) * U;
      const double denom = glm::dot(pl.normal, dir);
      if (denom == 0.0) continue;
      const double t = -d / denom;
      if (!(t > 0.0) || !std::isfinite(t)) continue;
      const dvec2 c = texel_coords(grids[p], eye + t * dir);
      box[p] = glm::dvec4(std::min(box[p].x, c.x), std::min(box[p].y, c.y), std::max(box[p].z, c.x), std::max(box[p].w, c.y));
    }
  };
  auto add_pixel = [&](uint32_t p, int x, int y) {
    dvec2 corners[4] = {{x, y}, {x + 1, y}, {x, y + 1}, {x + 1, y + 1}};
    if (!pinhole)
      for (dvec2& c : corners) c = undistort_pixel(cam, lens, c);
    add_points(p, corners);
  };
  // Through a lens: the parts of the regions of other polygons than p in the bounding box of
  // the pinhole image of the lens pixel (x, y).
  auto add_lens_pixel_regions = [&](uint32_t p, int x, int y, std::vector<dvec2>& clipped) {
    dvec2 lo(INFINITY), hi(-INFINITY);
    for (const dvec2 c : {dvec2(x, y), dvec2(x + 1, y), dvec2(x, y + 1), dvec2(x + 1, y + 1)}) {
      const dvec2 u = undistort_pixel(cam, lens, c);
      lo = glm::min(lo, u);
      hi = glm::max(hi, u);
    }
    for (int yy = std::max(0, int(std::floor(lo.y))); yy <= std::min(H - 1, int(std::floor(hi.y))); ++yy)
      for (int xx = std::max(0, int(std::floor(lo.x))); xx <= std::min(W - 1, int(std::floor(hi.x))); ++xx)
        for (uint32_t r : regions_at(xx, yy))
          if (const MapRegion& reg = vis_map->regions[r]; reg.polygon != p) {
            clip_to_rect(reg.vertices, lo, hi, clipped);
            add_points(reg.polygon, clipped);
          }
  };
  std::vector<dvec2> clipped;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const uint32_t p = labels.at(x, y);
      if (p != kNone) {
        ++out.pixels_mapped;
        add_pixel(p, x, y);
      } else if (sub) {
        for (int k = 0; k < 2; ++k)
          if (any_bits(x, y, k)) add_pixel(labels.at(x, y, 1 + k), x, y);
      }
      if (exact && boundary.at(x, y) && !pinhole) {
        add_lens_pixel_regions(p, x, y, clipped);
      } else if (exact && boundary.at(x, y)) {
        // Only the part of each region inside the pixel: a sliver of a polygon seen edge-on
        // would otherwise stretch its box over the whole polygon.
        for (uint32_t r : regions_at(x, y))
          if (const MapRegion& reg = vis_map->regions[r]; reg.polygon != p) {
            clip_to_pixel(reg.vertices, x, y, clipped);
            add_points(reg.polygon, clipped);
          }
      }
    }
  std::sort(seen.begin(), seen.end());
  for (uint32_t p : seen) {
    const TexelGrid& g = grids[p];
    const glm::dvec4 b = box[p];
    if (!(b.x <= b.z)) continue;
    const int i0 = std::max(0, int(std::floor(b.x)) - 1), j0 = std::max(0, int(std::floor(b.y)) - 1);
    const int i1 = std::min(g.width, int(std::ceil(b.z)) + 1), j1 = std::min(g.height, int(std::ceil(b.w)) + 1);
    if (i0 >= i1 || j0 >= j1) continue;
    SampleLayer L;
    L.photo = photo;
    L.x0 = i0;
    L.y0 = j0;
    L.width = i1 - i0;
    L.height = j1 - j0;
    L.rgba.assign(size_t(L.width) * size_t(L.height), 0u);
    int fi0 = i1, fj0 = j1, fi1 = i0 - 1, fj1 = j0 - 1;
    // The polygon in texel coordinates (counter-clockwise: u × v is its normal). Only texel
    // centers on the polygon get samples: one off it (in the grid's margin) can project
    // into a mapped pixel yet lie behind a neighbor polygon.
    std::vector<dvec2> outline;
    for (const dvec3& q : model.polygons[p].vertices) outline.push_back(texel_coords(g, q));
    auto on_polygon = [&](double tx, double ty) {
      for (size_t k = 0; k < outline.size(); ++k) {
        const dvec2 e = outline[(k + 1) % outline.size()] - outline[k], r = dvec2(tx, ty) - outline[k];
        if (e.x * r.y - e.y * r.x < 0.0) return false;
      }
      return true;
    };
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        if (!on_polygon(i + 0.5, j + 0.5)) continue;
        const dvec3 d = texel_center(g, i, j) - eye;
        const double z = glm::dot(d, F);
        if (z <= 0.0) continue;
        const double ux = cx + f * glm::dot(d, R) / z, uy = cy - f * glm::dot(d, U) / z;
        // (px, py): the point in the photograph (through the lens), (ux, uy) in the pinhole image.
        const dvec2 q = pinhole ? dvec2(ux, uy) : distort_pixel(cam, lens, {ux, uy});
        const double px = q.x, py = q.y;
        if (!(px >= 0.0 && py >= 0.0 && px < W && py < H)) continue;
        const int ix = int(px), iy = int(py);
        const bool direct = labels.at(ix, iy) == p;
        if (!direct && exact) {
          // A pixel that may show p in part: is the projection itself in a region of p?
          if (!boundary.at(ix, iy)) continue;  // wholly on another polygon
          if (!(ux >= 0.0 && uy >= 0.0 && ux < W && uy < H)) continue;  // outside the map
          bool seen_here = false;
          for (uint32_t r : regions_at(int(ux), int(uy)))
            if (vis_map->regions[r].polygon == p && inside_region(vis_map->regions[r], dvec2(ux, uy))) {
              seen_here = true;
              break;
            }
          if (!seen_here) continue;
        } else if (!direct) {
          // A pixel touching a silhouette: is the sub-cell holding the projection wholly on p?
          if (!sub) continue;
          const int s = std::min(kSubCells - 1, int((px - ix) * kSubCells)) +
                        kSubCells * std::min(kSubCells - 1, int((py - iy) * kSubCells));
          if (!((labels.at(ix, iy, 1) == p && record_bit(labels, ix, iy, 0, s)) ||
                (labels.at(ix, iy, 2) == p && record_bit(labels, ix, iy, 1, s))))
            continue;
        }
        // Bilinear over the pixel centers around (px, py) that map onto p (exact-visible
        // texels: or are unmixed for p).
        const double sx = px - 0.5, sy = py - 0.5;
        const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
        const double fx = sx - x0, fy = sy - y0;
        vec3 c(0.0f);
        double wsum = 0.0;
        bool used_unmixed = false;
        for (int k = 0; k < 4; ++k) {
          const int xx = x0 + (k & 1), yy = y0 + (k >> 1);
          if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
          const bool clean = labels.at(xx, yy) == p, unmixed = !direct && unmix && labels.at(xx, yy, uc) == p;
          if (!clean && !unmixed) continue;
          const double w = ((k & 1) ? fx : 1.0 - fx) * ((k >> 1) ? fy : 1.0 - fy);
          c += float(w) * (clean ? rgb_at(image, xx, yy) : unpack_srgb8(labels.at(xx, yy, uc + 1)));
          wsum += w;
          used_unmixed = used_unmixed || (unmixed && w > 0.0);
        }
        if (wsum <= 0.0) {
          // Exact-visible texel with no wholly-on-p pixel among the 2 × 2: the nearest within 2 px.
          double best = 4.0 + 1e-9;
          for (int yy = iy - 2; yy <= iy + 2; ++yy)
            for (int xx = ix - 2; xx <= ix + 2; ++xx) {
              if (xx < 0 || yy < 0 || xx >= W || yy >= H || labels.at(xx, yy) != p) continue;
              const double dd = (xx + 0.5 - px) * (xx + 0.5 - px) + (yy + 0.5 - py) * (yy + 0.5 - py);
              if (dd < best) best = dd, c = rgb_at(image, xx, yy), wsum = 1.0;
            }
        }
        uint32_t alpha = direct ? 0xFFu : used_unmixed ? kUnmixed : kExtrapolated;
        if (wsum <= 0.0) {
          // No pixel wholly on p near it (a sliver of p along a silhouette): the pixel's own,
          // mixed color, flagged as a last resort for holes (novel_view.h).
          c = rgb_at(image, ix, iy);
          wsum = 1.0;
          alpha = kMixed;
        }
        const uint32_t packed = (pack_srgb8(c / float(wsum)) & 0x00FFFFFFu) | (alpha << 24);
        L.rgba[size_t(j - j0) * size_t(L.width) + size_t(i - i0)] = packed;
        L.mixed += alpha == kMixed;
        fi0 = std::min(fi0, i);
        fj0 = std::min(fj0, j);
        fi1 = std::max(fi1, i);
        fj1 = std::max(fj1, j);
      }
    if (fi1 < fi0) continue;
    // Shrink to the samples' rectangle.
    SampleLayer S;
    S.photo = photo;
    S.mixed = L.mixed;
    S.x0 = fi0;
    S.y0 = fj0;
    S.width = fi1 - fi0 + 1;
    S.height = fj1 - fj0 + 1;
    S.rgba.resize(size_t(S.width) * size_t(S.height));
    for (int j = 0; j < S.height; ++j)
      std::copy_n(L.rgba.begin() + long(size_t(j + fj0 - j0) * size_t(L.width) + size_t(fi0 - i0)), S.width,
                  S.rgba.begin() + long(size_t(j) * size_t(S.width)));
    fill_reach(S);
    out.layers.push_back({p, std::move(S)});
  }
  return out;
}

}  // namespace

namespace {

// Chessboard distance from each texel of L to the nearest sample with alpha ≥ min_alpha, capped
// at 255: the two-pass 3 × 3 transform (exact for this metric, and the cap commutes with its
// min-plus steps) on a buffer with a 255 border, reduced to the least value per block.
std::vector<uint8_t> block_reach(const SampleLayer& L, uint32_t min_alpha) {
  const int W = L.width, H = L.height;
  const size_t stride = size_t(W) + 2;
  std::vector<uint8_t> d(stride * (size_t(H) + 2), 255);
  // The running value stays in a register (no reload of the texel just stored).
  auto step = [](int a, int b, int c, int e) { return std::min(255, 1 + std::min(std::min(a, b), std::min(c, e))); };
  for (int j = 0; j < H; ++j) {
    uint8_t* r = d.data() + (size_t(j) + 1) * stride + 1;
    const uint8_t* up = r - stride;
    const uint32_t* t = L.rgba.data() + size_t(j) * size_t(W);
    int prev = 255;
    for (int i = 0; i < W; ++i) {
      const int v = (t[i] >> 24) >= min_alpha ? 0 : step(prev, up[i - 1], up[i], up[i + 1]);
      r[i] = uint8_t(v);
      prev = v;
    }
  }
  for (int j = H - 1; j >= 0; --j) {
    uint8_t* r = d.data() + (size_t(j) + 1) * stride + 1;
    const uint8_t* down = r + stride;
    int prev = 255;
    for (int i = W - 1; i >= 0; --i) {
      const int v = std::min(int(r[i]), step(prev, down[i - 1], down[i], down[i + 1]));
      r[i] = uint8_t(v);
      prev = v;
    }
  }
  const int bw = L.reach_columns(), bh = (H + kReachBlock - 1) / kReachBlock;
  std::vector<uint8_t> out(size_t(bw) * size_t(bh), 255);
  for (int j = 0; j < H; ++j) {
    const uint8_t* r = d.data() + (size_t(j) + 1) * stride + 1;
    uint8_t* o = out.data() + size_t(j / kReachBlock) * size_t(bw);
    for (int i = 0; i < W; ++i) o[i / kReachBlock] = std::min(o[i / kReachBlock], r[i]);
  }
  return out;
}

}  // namespace

void fill_reach(SampleLayer& L) {
  L.reach = block_reach(L, kExtrapolated);
  L.reach_mixed = L.mixed > 0 ? block_reach(L, kMixed) : std::vector<uint8_t>{};
}

PhotoLayers map_photo_layers(const ModelPolygons& model, const std::vector<TexelGrid>& grids, uint32_t photo,
                             const Camera& camera, const ImageF& image, const ImageU32& pixel_polygons,
                             const VisibilityMap* vis_map, const Lens& lens) {
  return map_photo(model, grids, photo, camera, image, pixel_polygons, vis_map, lens);
}

RadianceMaps build_radiance_maps(const ModelPolygons& model, double texel, std::span<const Camera> cameras,
                                 std::span<const ImageF> photos, std::span<const ImageU32> pixel_polygons,
                                 std::span<const VisibilityMap> vis_maps) {
  if (cameras.size() != photos.size() || cameras.size() != pixel_polygons.size())
    fail_input("radiance maps: one image and one pixel mapping per camera");
  if (!vis_maps.empty() && vis_maps.size() != cameras.size())
    fail_input("radiance maps: one visibility map per camera, or none");
  for (size_t k = 0; k < vis_maps.size(); ++k)
    if (vis_maps[k].width != cameras[k].width || vis_maps[k].height != cameras[k].height)
      fail_input("radiance maps: a visibility map's size differs from its camera's");
  Stopwatch watch;
  const std::vector<TexelGrid> grids = make_texel_grids(model, texel);
  std::vector<PhotoLayers> per(cameras.size());
  parallel_for(cameras.size(), 1, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k)
      per[k] = map_photo(model, grids, uint32_t(k), cameras[k], photos[k], pixel_polygons[k],
                         vis_maps.empty() ? nullptr : &vis_maps[k], Lens{});
  });
  RadianceMaps maps = merge_photo_layers(grids, cameras, std::move(per));
  maps.stats.ms = watch.elapsed_ms();
  return maps;
}

namespace {

// Layers can come from outside the process (a sweep's photo.bin): each must fit its polygon's
// texel grid before the merge indexes with it.
void check_layer(const std::vector<TexelGrid>& grids, size_t photos, uint32_t polygon, const SampleLayer& L) {
  auto fail = [&](const std::string& what) {
    fail_input("gibr: a photograph's layer of polygon " + std::to_string(polygon) + " " + what);
  };
  if (polygon >= grids.size()) fail("names no polygon of the model");
  const TexelGrid& g = grids[polygon];
  if (L.photo >= photos) fail("names no photograph");
  if (L.x0 < 0 || L.y0 < 0 || L.width < 0 || L.height < 0 || L.x0 > g.width - L.width || L.y0 > g.height - L.height ||
      L.rgba.size() != size_t(L.width) * size_t(L.height))
    fail("lies outside its texel grid");
  const size_t blocks = size_t(L.reach_columns()) * size_t((L.height + kReachBlock - 1) / kReachBlock);
  if ((!L.reach.empty() && L.reach.size() != blocks) || (!L.reach_mixed.empty() && L.reach_mixed.size() != blocks))
    fail("has reach tables of the wrong size");
}

}  // namespace

RadianceMaps merge_photo_layers(const std::vector<TexelGrid>& grids, std::span<const Camera> cameras,
                                std::vector<PhotoLayers> per) {
  Stopwatch watch;
  RadianceMaps maps;
  maps.grids = grids;
  maps.layers.resize(grids.size());
  maps.cameras.assign(cameras.begin(), cameras.end());
  RadianceStats& s = maps.stats;
  s.photos = cameras.size();
  for (PhotoLayers& pl : per) {
    s.pixels_mapped += pl.pixels_mapped;
    for (auto& [p, layer] : pl.layers) {
      check_layer(grids, cameras.size(), p, layer);
      maps.layers[p].push_back(std::move(layer));
    }
  }
  for (size_t p = 0; p < maps.layers.size(); ++p) {
    const TexelGrid& g = maps.grids[p];
    s.texels += size_t(g.width) * size_t(g.height);
    if (maps.layers[p].empty()) continue;
    std::vector<uint8_t> covered(size_t(g.width) * size_t(g.height), 0);
    for (const SampleLayer& L : maps.layers[p]) {
      ++s.layers;
      s.bytes += L.rgba.size() * sizeof(uint32_t);
      for (int j = 0; j < L.height; ++j)
        for (int i = 0; i < L.width; ++i)
          if (const uint32_t a = L.rgba[size_t(j) * size_t(L.width) + size_t(i)] >> 24; a == kMixed) {
            ++s.samples_mixed;
          } else if (a != 0) {
            ++s.samples;
            s.samples_extrapolated += a == kExtrapolated;
            s.samples_unmixed += a == kUnmixed;
            covered[size_t(j + L.y0) * size_t(g.width) + size_t(i + L.x0)] = 1;
          }
    }
    for (uint8_t c : covered) s.texels_covered += c;
  }
  s.ms = watch.elapsed_ms();
  return maps;
}

}  // namespace proxima::gibr
