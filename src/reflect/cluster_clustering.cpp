// Screen-space clustering of reflective pixels.
// Paper: thesis ch. 4 §4.3 (聚类: i = MAXTHETABINS·θ/360°·a_R/n_v, j = MAXPHIBINS·φ/180°·a_R/n_v,
// k = p.rID). Symbols ↔ variables: MAXTHETABINS, MAXPHIBINS ↔ options.max_theta_bins,
// max_phi_bins; a_R ↔ share[R]; n_v ↔ visible; (i, j, k) ↔ (theta_bin, phi_bin, reflector).
// The printed scale a_R/n_v would give every reflector of a 20-reflector view a single bin
// (≈ 20 clusters), far from the 107–148 clusters the thesis reports; its text says bins
// grow with a reflector's screen share and shrink with the number of reflectors, and caps
// a reflector at 13 × 8 bins. We scale the bin *count* (θ bins × φ bins) with a_R·n_v, a
// reflector's share relative to the mean share: sqrt(a_R·n_v) per axis, at most 1, and at
// least options.min_bin_scale — a vase beside a floor holding 85% of the reflective pixels
// would otherwise get one cluster whose rays span more than any pinhole frustum holds.
#include "proxima/reflect/reflection_clustering.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>

namespace proxima {

namespace {

// A fixed, generic rotation: axis-aligned normals would otherwise lie on bin borders
// (φ = 90° with 8 bins) or at the pole where θ is undefined, and float noise in flat
// surfaces' normals would split them over several clusters.
const quat kBinFrame = glm::normalize(glm::angleAxis(0.2137f, glm::normalize(vec3(0.31f, 0.83f, 0.47f))));

int bin_count(int max_bins, double scale) {
  return std::max(1, int(std::ceil(double(std::max(1, max_bins)) * scale)));
}

}  // namespace

ReflectionClusters cluster_reflections(std::span<const vec3> normals, std::span<const uint32_t> reflectors,
                                       const ClusteringOptions& options) {
  assert(normals.size() == reflectors.size());
  ReflectionClusters out;
  const size_t n = normals.size();
  out.cluster_of.assign(n, 0);
  out.offsets.assign(1, 0);
  if (n == 0) return out;

  // a_R and n_v.
  std::map<uint32_t, uint64_t> pixels_of;
  for (uint32_t r : reflectors) ++pixels_of[r];
  const double visible = double(pixels_of.size());
  std::map<uint32_t, std::pair<int, int>> bins_of;  // reflector → (θ bins, φ bins)
  for (const auto& [r, count] : pixels_of) {
    double share = double(count) / double(n);
    double scale = std::clamp(std::sqrt(share * visible), double(std::clamp(options.min_bin_scale, 0.0f, 1.0f)), 1.0);
    bins_of[r] = {bin_count(options.max_theta_bins, scale), bin_count(options.max_phi_bins, scale)};
  }

  // Bucket key (reflector, φ bin, θ bin), ordered.
  std::vector<uint64_t> key(n);
  for (size_t i = 0; i < n; ++i) {
    vec3 d = kBinFrame * normals[i];
    double theta = std::atan2(double(d.z), double(d.x));  // azimuth
    if (theta < 0.0) theta += 2.0 * M_PI;
    double phi = std::acos(std::clamp(double(d.y), -1.0, 1.0));  // polar
    auto [tb, pb] = bins_of[reflectors[i]];
    uint64_t theta_bin = uint64_t(std::min(tb - 1, int(theta / (2.0 * M_PI) * tb)));
    uint64_t phi_bin = uint64_t(std::min(pb - 1, int(phi / M_PI * pb)));
    key[i] = (uint64_t(reflectors[i]) << 32) | (phi_bin << 16) | theta_bin;
  }
  std::vector<uint64_t> keys = key;
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

  out.offsets.assign(keys.size() + 1, 0);
  out.reflector.resize(keys.size());
  for (size_t c = 0; c < keys.size(); ++c) out.reflector[c] = uint32_t(keys[c] >> 32);
  for (size_t i = 0; i < n; ++i) {
    uint32_t c = uint32_t(std::lower_bound(keys.begin(), keys.end(), key[i]) - keys.begin());
    out.cluster_of[i] = c;
    ++out.offsets[c + 1];
  }
  for (size_t c = 0; c < keys.size(); ++c) out.offsets[c + 1] += out.offsets[c];
  out.members.resize(n);
  std::vector<uint32_t> fill(out.offsets.begin(), out.offsets.end() - 1);
  for (size_t i = 0; i < n; ++i) out.members[fill[out.cluster_of[i]]++] = uint32_t(i);
  return out;
}

}  // namespace proxima
