// Radiance maps (Funkhouser, section 2, phase 3; view-dependent texture maps after Debevec
// et al.): per input polygon a texel grid on its plane, and per photograph that sees the
// polygon a layer of samples, filled only from pixels the mapping assigns to the polygon.
//
// Mappings (which pixels of a photograph may color which polygon):
// - visibility map (Funkhouser): a pixel maps onto polygon P only when the pixel square lies
//   wholly inside P's regions of the photograph's exact visibility map, i.e. its center is
//   in a region of P and no silhouette edge (option: no map edge between different
//   polygons) passes within √2/2 px of its center (a conservative test of the square);
//   A pixel touching a silhouette is never mapped as it is; with unmixing, its color less
//   the other sides' (exact coverage from the map) colors P's exactly visible texels
//   (unmix_silhouette_pixels);
// - item buffer (Debevec-style baseline): the z-buffered polygon id at the pixel center, no
//   silhouette detection.
// Texel (i, j) of polygon P has its center at origin + (i + ½)·s·u + (j + ½)·s·v (s = texel
// size in meters, u, v unit axes in P's plane). It is filled from photograph k when its
// center projects into a pixel mapped onto P: the bilinear interpolation of the pixel
// centers around the projection, over the neighbors mapped onto P (weights renormalized).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/gibr/lens.h"
#include "proxima/scene/scene.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/visibility_map.h"

namespace proxima::gibr {

using visibility::kNone;
using glm::dvec2;

struct TexelGrid {
  dvec3 origin{0.0};             // corner (texel coordinates (0, 0))
  dvec3 u{1, 0, 0}, v{0, 1, 0};  // unit axes in the polygon's plane, u × v = plane normal
  double texel = 0.02;           // meters
  int width = 0, height = 0;     // texels
};

// Samples of one photograph on one polygon: a texel rectangle, sRGB 8-bit RGB + alpha
// (255 = sample, kUnmixed = sample colored partly from unmixed silhouette pixels,
// kExtrapolated = sample colored from neighboring pixels, kMixed = last-resort sample for
// holes, 0 = none), row-major.
struct SampleLayer {
  uint32_t photo = 0;
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::vector<uint32_t> rgba;  // r | g << 8 | b << 16 | a << 24
  size_t mixed = 0;            // kMixed samples (lets hole filling skip layers without any)
  // Lower bounds for the hole fill's ring search (fill_reach; empty = none): per block of
  // kReachBlock × kReachBlock texels of the rectangle (row-major, reach_columns() per row), the
  // least Chebyshev distance in texels from a texel of the block to a sample with alpha ≥
  // kExtrapolated (reach) or ≥ kMixed (reach_mixed, empty when mixed = 0), capped at 255.
  std::vector<uint8_t> reach, reach_mixed;

  int reach_columns() const;
  bool has(int i, int j) const {
    i -= x0;
    j -= y0;
    return i >= 0 && j >= 0 && i < width && j < height && (rgba[size_t(j) * size_t(width) + size_t(i)] >> 24) != 0;
  }
};

// Alpha of a sample whose texel is exactly visible in a pixel touching a silhouette, its color
// taken from neighboring pixels wholly on the polygon (blended like any other sample).
inline constexpr uint32_t kExtrapolated = 0x80;
// Alpha of an exact-visible sample whose bilinear color includes unmixed pixels
// (unmix_silhouette_pixels); blended like kExtrapolated ones (novel_view.h).
inline constexpr uint32_t kUnmixed = 0xC0;
// Alpha of a last-resort sample: an exact-visible texel with no pixel wholly on its polygon
// within 2 px takes its own (mixed) pixel's color; used only to fill holes (novel_view.h).
inline constexpr uint32_t kMixed = 0x40;

// Side of the blocks of SampleLayer::reach.
inline constexpr int kReachBlock = 4;
inline int SampleLayer::reach_columns() const { return (width + kReachBlock - 1) / kReachBlock; }
// Fills L.reach and L.reach_mixed from L.rgba (an exact chessboard distance transform, then the
// least value of each block). build_radiance_maps calls it for every layer.
void fill_reach(SampleLayer& L);

struct RadianceStats {
  size_t photos = 0;
  size_t layers = 0;            // (polygon, photograph) pairs with ≥ 1 sample
  size_t samples = 0;           // texel samples over all layers
  size_t samples_extrapolated = 0;  // of which exact-visible texels in silhouette pixels
  size_t samples_unmixed = 0;   // of which exact-visible, colored partly from unmixed pixels
  size_t samples_mixed = 0;     // last-resort samples (kMixed), not in `samples`
  size_t texels = 0;            // texels of all grids
  size_t texels_covered = 0;    // texels with ≥ 1 sample
  size_t pixels_mapped = 0;     // photograph pixels mapped onto some polygon
  size_t bytes = 0;             // sample storage
  double ms = 0.0;              // mapping (phase 3) wall time, labels excluded
};

struct RadianceMaps {
  std::vector<TexelGrid> grids;                 // per polygon
  std::vector<std::vector<SampleLayer>> layers; // per polygon, in photograph order
  std::vector<Camera> cameras;                  // per photograph
  RadianceStats stats;
};

// Texel grids of every polygon: u along the polygon's first edge, the rectangle its
// vertices span plus one texel on every side. texel > 0 (InputError otherwise); a polygon
// needing more than 2^26 texels throws InputError.
std::vector<TexelGrid> make_texel_grids(const visibility::ModelPolygons& model, double texel);

// Sub-cells per pixel side of the visibility map's sub-pixel record (see below), the 32-bit
// words of one polygon's sub-cell bits, and the record's channels.
inline constexpr int kSubCells = 8;
inline constexpr int kMaskWords = kSubCells * kSubCells / 32;
inline constexpr int kRecordChannels = 3 + 2 * kMaskWords;
// Sub-cell s (row-major) of pixel (x, y) of a sub-pixel record lies wholly on side k (0 = A, 1 = B).
inline bool record_bit(const ImageU32& labels, int x, int y, int k, int s) {
  return (labels.at(x, y, 3 + k * kMaskWords + s / 32) >> (s % 32)) & 1u;
}

// Visibility-map mapping: channel 0 is per pixel the polygon it maps onto, kNone for a pixel
// that is not wholly inside one polygon's regions (or sees the background). With `subpixel`
// (kRecordChannels channels) a pixel touching a silhouette also records which of its
// kSubCells² sub-cells lie wholly inside a polygon's regions (the same test on the map scaled
// by kSubCells): channels 1 and 2 hold up to two polygons A, B (kNone if absent), channels
// 3 … 3 + kMaskWords − 1 the sub-cell bits of A (row-major), the next kMaskWords those of B
// (record_bit). Its color is still never mapped:
// a texel whose center projects into such a sub-cell of P is exactly visible and takes its
// color from the nearest pixels wholly on P (build_radiance_maps).
ImageU32 vismap_pixel_polygons(const visibility::VisibilityMap& map, bool exclude_all_boundaries = false,
                               bool subpixel = true);

// Unmixing of pixels touching a silhouette (labels: vismap_pixel_polygons' labels of the same
// map and options, 1 channel or the sub-pixel record; photo: that photograph, linear RGB, rendered with s × s
// samples per pixel at the cell centers of a regular grid). The map gives, exactly, the
// share α_Q of the pixel's s × s samples that see each polygon Q (or the background): the
// photograph's pixel filter, so the pixel's color is c = Σ α_Q c_Q. Where one polygon P has
// α_P ≥ ½ and the color c_Q of every other side is known — the nearest pixel within 2 px
// wholly inside Q's regions (touching no map edge between different polygons; Q may be the
// background) — P's own
// color is c_P = (c − Σ_{Q≠P} α_Q c_Q) / α_P, clamped to [0, 1]. Returns the labels with two
// more channels (unmix_channel): P (kNone where the pixel is not unmixed), then
// pack_srgb8(c_P).
// (For a box-filtered camera α would be P's area of the pixel; the synthetic photographs
// average point samples, so their α is the share of samples.)
// With `two_pass`, a side with no pixel wholly on it within 2 px (a thin occluder, a jamb
// seen edge-on) takes its color from the nearest pixel within 2 px unmixed for it in a first
// pass, and pixels the first pass could not unmix are tried again (first-pass colors only).
ImageU32 unmix_silhouette_pixels(const visibility::VisibilityMap& map, const ImageU32& labels, const ImageF& photo,
                                 int samples, bool exclude_all_boundaries = false, bool two_pass = false);

// What the unmixing reads from a photograph's visibility map, per pixel of the photograph:
// `centers` the polygon at its center (kNone: background, or not known), `touched` 1 for the
// pixels to unmix (touching a silhouette — with exclude_all_boundaries any edge between
// different polygons), `on_any_edge` 1 for pixels touching an edge between different polygons
// (not wholly on one: the other sides' colors come from the others), and `fine` (width·s ×
// height·s) the polygon each of the pixel's s × s samples sees (all known where touched).
struct UnmixInputs {
  ImageU32 centers, fine;
  ImageU8 touched, on_any_edge;
  int samples = 1;
};
// unmix_silhouette_pixels from those inputs (it builds them from the map: rasterized pixel
// centers, the map scaled ×s; gibr/lens_mapping.h builds them through a lens). InputError
// when the sizes disagree or samples is outside 1..8.
ImageU32 unmix_pixels(const ImageU32& labels, const ImageF& photo, const UnmixInputs& inputs, bool two_pass);

// First of unmix_silhouette_pixels' two channels in labels (1 + 2 or kRecordChannels + 2
// channels), −1 for labels without them.
inline int unmix_channel(const ImageU32& labels) {
  const int c = labels.channels();
  return c == 3 || c == kRecordChannels + 2 ? c - 2 : -1;
}

// 1 where a pixel center lies within `radius` px of a silhouette edge of the map, else 0.
ImageU8 silhouette_pixel_mask(const visibility::VisibilityMap& map, double radius);

// Item-buffer mapping: the rasterized (z-buffer) polygon at each pixel center.
ImageU32 itembuffer_pixel_polygons(const Scene& scene, const visibility::ModelPolygons& model, const Camera& camera);

// Builds the layers of every photograph from its image and pixel → polygon mapping (same
// sizes as the camera; 1 channel, kRecordChannels as vismap_pixel_polygons' sub-pixel record, or 2 more with
// unmix_silhouette_pixels' channels). A texel of P is sampled when its center projects into
// a pixel mapped onto P ("direct": bilinear over the 2 × 2 pixel centers around the
// projection that map onto P, alpha 255) or, in a pixel not mapped onto P, exactly onto P
// ("exact-visible") — with `vis_maps` (the photographs' visibility maps, the labels' source)
// when the pixel may show P (label kNone, or beside a pixel with another label: a crease)
// and the projection lies in a region of P (point-in-convex-polygon, ≥ 10⁻³ px inside its
// edges); without, when it lies in a sub-cell of the sub-pixel record wholly inside P (the same
// bilinear over pixels mapped onto P or
// unmixed for P — alpha kUnmixed when an unmixed one is among them, else kExtrapolated —
// else the nearest pixel center within 2 px mapped onto P, alpha kExtrapolated; with none,
// the pixel's own mixed color, alpha kMixed, for holes only).
// Parallel over photographs; the result does not depend on threads.
RadianceMaps build_radiance_maps(const visibility::ModelPolygons& model, double texel, std::span<const Camera> cameras,
                                 std::span<const ImageF> photos, std::span<const ImageU32> pixel_polygons,
                                 std::span<const visibility::VisibilityMap> vis_maps = {});

// One photograph's layers (build_radiance_maps' per-photograph step): (polygon, layer) pairs
// in polygon order, and its pixels mapped onto some polygon.
struct PhotoLayers {
  std::vector<std::pair<uint32_t, SampleLayer>> layers;
  size_t pixels_mapped = 0;
};

// The layers photograph `photo` (index into the maps' cameras) adds, as build_radiance_maps
// makes them (grids: make_texel_grids of the model and texel; vis_map may be null). With a
// `lens` (gibr/lens.h), `image` and `pixel_polygons` are the photograph as the lens took it,
// not resampled (gibr/lens_mapping.h): a texel center is projected through the pinhole
// camera, then through the lens, and the image is sampled there once; the exact-visible test
// runs at the pinhole point, in the map.
PhotoLayers map_photo_layers(const visibility::ModelPolygons& model, const std::vector<TexelGrid>& grids,
                             uint32_t photo, const Camera& camera, const ImageF& image, const ImageU32& pixel_polygons,
                             const visibility::VisibilityMap* vis_map, const Lens& lens = {});

// The radiance maps of every photograph's layers (`per`, in photograph order: each polygon's
// layers come out in photograph order, whatever computed them where) and their statistics;
// stats.ms is the merge's time.
RadianceMaps merge_photo_layers(const std::vector<TexelGrid>& grids, std::span<const Camera> cameras,
                                std::vector<PhotoLayers> per);

// Texel coordinates (continuous, texel centers at +0.5) of a world point on the grid's plane.
inline dvec2 texel_coords(const TexelGrid& g, const dvec3& p) {
  const dvec3 d = p - g.origin;
  return {glm::dot(d, g.u) / g.texel, glm::dot(d, g.v) / g.texel};
}
inline dvec3 texel_center(const TexelGrid& g, int i, int j) {
  return g.origin + ((i + 0.5) * g.texel) * g.u + ((j + 0.5) * g.texel) * g.v;
}

// sRGB 8-bit packing of linear RGB (clamped to [0, 1]) and back.
uint32_t pack_srgb8(const vec3& linear);
vec3 unpack_srgb8(uint32_t rgba);

}  // namespace proxima::gibr
