// Reflection offset (thesis ch. 5 §5.4.2): forward warp of the key frame's pixel grid mesh
// (two triangles per 2×2 block of reflective pixels of one reflector) with every vertex
// moved by its best-match offset, into an intermediate image on the key frame's pixel grid.
// Vertices carry s.Lr; the depth test uses s.d + s.r so the nearer reflected surface wins
// where warped reflections overlap. Triangles stretched by more than `stretch_limit` in area
// are drawn but mark their pixels unreliable, and so are triangles on a strongly curved
// reflector (a corner's mirror_spread above `spread_limit`: there the reflector minifies the
// scene so much that a sub-pixel shift changes what a pixel shows, which no reuse predicts); triangles across a depth discontinuity (or
// with an INVALID corner) are not drawn, so the gaps they leave stay empty. Empty and
// unreliable pixels are recomputed by the ray tracer. Valid samples that no triangle
// covers are splatted as points onto the nearest pixel, if it is still empty.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "proxima/core/image.h"
#include "proxima/core/large_buffer.h"
#include "proxima/reflect/temporal_best_match.h"
#include "proxima/reflect/temporal_depth_image.h"

namespace proxima {

// kWarpCurved: unreliable because the reflector is strongly curved there (spread_limit),
// which a new key frame would not change; kWarpEdge: on an edge of the reflected image
// (edge_contrast with ReflectedEdgeRule::kRecompute), which a new key frame would not change either.
enum WarpState : uint8_t { kWarpEmpty = 0, kWarpReliable = 1, kWarpUnreliable = 2, kWarpCurved = 3, kWarpEdge = 4 };

// What a reused pixel does inside an edge triangle (corners' s·Lr differ by more than
// edge_contrast): blending a point-sampled edge puts a value that is on neither side of it.
enum class ReflectedEdgeRule : uint8_t {
  kNearest,    // take the Lr of the triangle's corner nearest the pixel (largest barycentric)
  kRecompute,  // mark the triangle's pixels kWarpEdge: recomputed by the ray tracer
};
const char* reflected_edge_rule_name(ReflectedEdgeRule rule);  // "nearest" | "recompute"
// Throws InputError "<flag>: must be nearest or recompute" for any other name.
ReflectedEdgeRule parse_reflected_edge_rule(const std::string& name, const char* flag);

struct WarpOptions {
  float stretch_limit = 16.0f;        // warped / original triangle area above this → unreliable
  float depth_discontinuity = 0.1f;   // corners whose s.d or s.d + s.r differ by more than this
                                      // fraction (max/min − 1) are not connected
  float spread_limit = kInf;          // off by default (docs/temporal.md); triangles with a corner whose mirror_spread exceeds this
                                      // (strongly curved reflector) are unreliable, unless the
                                      // corner's glossy lobe is wider than the reflected angle
                                      // one key pixel spans (spread / focal px); inf = off
  float curved_contrast = 0.05f;      // ... and only where s·Lr differs from a 4-neighbour's on
                                      // the same reflector by more than this (linear, any channel):
                                      // a curved mirror showing a smooth wall is safe to reuse;
                                      // negative: every curved pixel
  float edge_contrast = kInf;         // off by default: triangles whose corners' s·Lr differ by more
                                      // than this (linear, any channel) span an edge of the
                                      // reflected image and follow edge_rule
  ReflectedEdgeRule edge_rule = ReflectedEdgeRule::kNearest;
  bool recompute_splats = false;      // splatted points (no triangle reached them) are unreliable:
                                      // their value is a lone sample read by the bilinear fallback
  float blend_error = kInf;           // off by default: a reused sample whose expected display error
                                      // (blend_risk, 0–255) exceeds this is recomputed (kReuseEdge)
};

// The key samples a reused value blends and their weights: a warp triangle's three corners
// (barycentrics) or the reprojection's bilinear fallback (up to four pixels).
struct BlendSamples {
  vec3 lr[4];
  float w[4];
  int n = 0;
};

// The expected display error (0–255 per channel, sRGB of the clamped value, as
// eval/image_error measures) of reusing `value` in the composite base + s·Lr: the max over
// channels of Σ w_k·|D(base + s·Lr_k) − D(base + s·value)| / Σ w_k — the error if the true
// reflection were sample k with probability w_k. A point-sampled reflected edge between
// samples is as likely on either side; near a sample, between similar samples, or where the
// display saturates or the reflection is faint, the risk is small.
float blend_risk(const BlendSamples& blend, vec3 value, float s, vec3 base);

// blend_risk(blend, value, s, base) > limit, the same decision for every input: a table
// for the sRGB curve settles it unless the risk is within a bound of `limit` (then, and for
// NaN input, the exact blend_risk decides), so most samples take no powf.
bool blend_risk_exceeds(const BlendSamples& blend, vec3 value, float s, vec3 base, float limit);

// The table blend_risk_exceeds reads: linear_to_srgb for l in [0, 1] within
// linear_to_srgb_approx_error(). For its test.
float linear_to_srgb_approx(float l);
float linear_to_srgb_approx_error();

// True when the corners' s·Lr (s = key.specular) differ by more than `contrast` in a channel.
bool edge_triangle(const ReflectionDepthImage& key, const int corner_x[3], const int corner_y[3], float contrast);

inline constexpr uint32_t kNoWarpTriangle = 0xFFFFFFFFu;

// A warp triangle that the key frame alone admits (corners reflective, on one reflector):
// its corners' indices in key.pixels and what the key frame says about it. Per frame only
// the corners' offset validity and the stretch remain to test.
struct WarpCandidate {
  uint32_t corner[3];
  uint8_t half;   // of its grid quad at key.pixels[corner[0]]
  uint8_t flags;  // kCandidate* bits
};
inline constexpr uint8_t kCandidateDiscontinuous = 1, kCandidateCurved = 2, kCandidateEdge = 4;

// A key pixel's vertex data that does not move: depth s.d + s.r and s.Lr.
struct WarpSample {
  float z;
  vec3 lr;
};

struct IntermediateReflection {
  ImageF radiance;    // 3 channels, interpolated s.Lr of the nearest warped triangle
  ImageF depth;       // its interpolated s.d + s.r, +inf where empty
  ImageU8 state;      // WarpState
  ImageU32 triangle;  // that triangle: 2·(y·width + x) + half of its grid quad, or kNoWarpTriangle
  // Per reflective key pixel, in key.pixels order (compact: far less memory than per pixel):
  std::vector<vec2> point;      // per frame: its centre moved by its offset
  std::vector<uint8_t> valid;   // per frame: its offset is valid
  std::vector<uint32_t> written;  // the key's reflective pixels: the only ones a warp writes
  // Per key frame (rebuilt when the key's serial, its size or the options they read change):
  uint64_t key_serial = 0;        // ReflectionDepthImage::serial they were made for; 0: none
  uint32_t key_options[4] = {};   // bits of depth_discontinuity, spread_limit, curved_contrast, edge_contrast
  std::vector<WarpSample> sample;   // per reflective key pixel: z and Lr of its vertex
  std::vector<uint8_t> flat;        // likewise: not on a strongly curved reflector
  LargeBuffer<uint32_t> index;      // per key pixel (row-major): its index in key.pixels, set
                                    // on reflective pixels only
  std::vector<WarpCandidate> candidates;  // in the warp's triangle order
  uint64_t triangles = 0, stretched = 0, curved = 0, discontinuous = 0, edges = 0;
};

// Deterministic for any thread count: each pixel takes the triangles covering it in one fixed
// order (one pass on one thread, fixed row bands on more).
IntermediateReflection warp_reflections(const ReflectionDepthImage& key, const OffsetBuffer& offsets,
                                        const WarpOptions& options);

// The same into `out` (empty, or from an earlier warp), reusing its buffers from an earlier
// warp of the same size (per frame only its written pixels are reset, not four whole
// images): the same result.
void warp_reflections_into(const ReflectionDepthImage& key, const OffsetBuffer& offsets, const WarpOptions& options,
                           IntermediateReflection& out);

// The warped mesh, for reading it at any point of the key grid.
struct WarpedMesh {
  const ReflectionDepthImage* key = nullptr;
  const OffsetBuffer* offsets = nullptr;
  const IntermediateReflection* image = nullptr;
  float edge_contrast = kInf;  // WarpOptions::edge_contrast of the warp: edge triangles give their
                               // nearest corner's Lr (under kRecompute they are not reliable)
  ReflectedEdgeRule edge_rule = ReflectedEdgeRule::kNearest;
  bool recompute_splats = false;      // splatted points (no triangle reached them) are unreliable:
                                      // their value is a lone sample read by the bilinear fallback
  float blend_error = kInf;           // WarpOptions::blend_error of the warp
};

// s.Lr of the warped mesh at continuous key-grid position q: the reliable triangles stored
// in the 3×3 pixels around q, in a fixed order, evaluated at q itself. Reading the mesh
// rather than the image's pixel centres resamples the key frame once, not twice (warp, then
// bilinear reprojection). False when none of them contains q. With `blend`, also the
// triangle's corners and their weights at q.
bool warped_radiance_at(const WarpedMesh& mesh, vec2 q, vec3& radiance, BlendSamples* blend = nullptr);

}  // namespace proxima
