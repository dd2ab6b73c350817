// Screen-space clustering of reflective pixels (thesis ch. 4 §4.3): each pixel goes to the
// bucket (θ bin, φ bin, reflector id) of its normal's spherical coordinates, with bin counts
// MAXTHETABINS × MAXPHIBINS scaled per reflector by its share of the reflective pixels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/math.h"

namespace proxima {

struct ClusteringOptions {
  int max_theta_bins = 13;  // MAXTHETABINS: azimuth bins over 360° for a full-share reflector
  int max_phi_bins = 8;     // MAXPHIBINS: polar bins over 180°
  // Lower bound of the per-reflector bin scale: a curved reflector with a small screen
  // share still gets ≥ this fraction of the bins per axis, so that a cluster's normals span
  // at most ~55° × 45° and its reflection rays fit one pinhole frustum. 0 = no bound.
  float min_bin_scale = 0.5f;
};

// Clusters as index lists: cluster c owns members[offsets[c] .. offsets[c+1]), ascending
// sample indices. Clusters are ordered by (reflector, φ bin, θ bin), so the numbering does
// not depend on pixel order or threads.
struct ReflectionClusters {
  std::vector<uint32_t> cluster_of;  // per sample: its cluster
  std::vector<uint32_t> offsets;     // size count() + 1
  std::vector<uint32_t> members;     // sample indices grouped by cluster
  std::vector<uint32_t> reflector;   // per cluster: the reflector (object) id, p.rID

  size_t count() const { return reflector.size(); }
  std::span<const uint32_t> cluster(size_t c) const {
    return std::span<const uint32_t>(members).subspan(offsets[c], offsets[c + 1] - offsets[c]);
  }
};

// Clusters samples by their unit normals and reflector ids (normals.size() == reflectors.size()).
// Per reflector R: a_R = its samples / all samples, n_v = reflectors with samples; bins per
// axis are ceil(MAX·clamp(sqrt(a_R·n_v), min_bin_scale, 1)), at least 1
// (docs/cluster_reflections.md explains the scale).
// Angles are taken in a fixed generic frame so axis-aligned normals (walls, floors) sit
// inside a bin rather than on a bin border or at the pole. Options < 1 are treated as 1.
ReflectionClusters cluster_reflections(std::span<const vec3> normals, std::span<const uint32_t> reflectors,
                                       const ClusteringOptions& options = {});

}  // namespace proxima
