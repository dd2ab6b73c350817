// Mesh reconstruction from depth images.
// Paper: Xie Naiwen, PhD thesis (Beihang), ch. 3 §3.2 (../shared/papers/004_d1af2812aec5f9c7.txt,
// lines 826–884): the conventional mesh reconstruction and Algorithm 4, the hybrid
// reconstruction of (non-redundant) depth images.
//
// Symbol ↔ variable:
//   I, e           image (DepthImage), image.camera.position
//   H              offset (rendered with half_pixel_offset_camera)
//   p, s, n        pixel (x, y), its sample point points[k], normal normals[k]
//   c0 … c3        corners (x,y), (x,y+1), (x+1,y+1), (x+1,y) of pixel p
//   r, plane       ray_through(camera, corner), plane through s with normal n
//   M              the returned Mesh
#include "proxima/reconstruct/reconstruction.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "proxima/core/parallel.h"

namespace proxima {

bool same_surface(vec3 p, vec3 n, float depth, float focal_px, vec3 q) {
  return std::abs(glm::dot(n, q - p)) <= kContinuityTolerance * depth / focal_px;
}

namespace {

constexpr size_t kRowGrain = 8;  // rows per parallel chunk

// Sample points and normals of an image, row-major; valid[k] = the pixel holds a sample.
struct Samples {
  int width = 0, height = 0;
  float focal = 1.0f;
  std::vector<vec3> points, normals;
  std::vector<float> depth;
  std::vector<uint8_t> valid;

  size_t index(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  bool has(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height && valid[index(x, y)]; }
};

Samples gather(const DepthImage& image) {
  assert(!image.normal.empty() && "reconstruction needs the normal image (shade = true)");
  Samples s;
  s.width = image.depth.width();
  s.height = image.depth.height();
  s.focal = focal_length_px(image.camera);
  const size_t n = size_t(s.width) * size_t(s.height);
  s.points.assign(n, vec3(0.0f));
  s.normals.assign(n, vec3(0.0f));
  s.depth.assign(n, kInf);
  s.valid.assign(n, 0);
  parallel_for(size_t(s.height), kRowGrain, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y) {
      for (int x = 0; x < s.width; ++x) {
        if (image.triangle.at(x, y) == kNoTriangle) continue;
        const size_t k = s.index(x, y);
        s.valid[k] = 1;
        s.depth[k] = image.depth.at(x, y);
        s.points[k] = sample_point(image, x, y);
        s.normals[k] = vec3(image.normal.at(x, y, 0), image.normal.at(x, y, 1), image.normal.at(x, y, 2));
      }
    }
  });
  return s;
}

bool continuous(const Samples& s, size_t a, size_t b) {
  return same_surface(s.points[a], s.normals[a], s.depth[a], s.focal, s.points[b]) &&
         same_surface(s.points[b], s.normals[b], s.depth[b], s.focal, s.points[a]);
}

// Exclusive prefix sum of per-row counts; returns the total.
size_t prefix(std::vector<size_t>& counts) {
  size_t total = 0;
  for (size_t& c : counts) {
    const size_t n = c;
    c = total;
    total += n;
  }
  return total;
}

}  // namespace

Mesh reconstruct_conventional(const DepthImage& image) {
  const Samples s = gather(image);
  Mesh mesh;
  // One vertex per sample, in row-major order.
  std::vector<uint32_t> vertex(s.valid.size(), 0);
  for (size_t k = 0; k < s.valid.size(); ++k) {
    if (!s.valid[k]) continue;
    vertex[k] = uint32_t(mesh.positions.size());
    mesh.positions.push_back(s.points[k]);
    mesh.normals.push_back(s.normals[k]);
  }
  if (s.width < 2 || s.height < 2) return mesh;
  // Per quad: bit 0 = triangle (x,y)(x,y+1)(x+1,y+1), bit 1 = (x+1,y+1)(x+1,y)(x,y).
  const int qw = s.width - 1, qh = s.height - 1;
  std::vector<uint8_t> emit(size_t(qw) * size_t(qh), 0);
  std::vector<size_t> row_count(size_t(qh), 0);
  auto ok = [&](size_t a, size_t b, size_t c) {
    return s.valid[a] && s.valid[b] && s.valid[c] && continuous(s, a, b) && continuous(s, b, c) && continuous(s, c, a);
  };
  parallel_for(size_t(qh), kRowGrain, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y) {
      for (int x = 0; x < qw; ++x) {
        const size_t a = s.index(x, y), b = s.index(x, y + 1), c = s.index(x + 1, y + 1), d = s.index(x + 1, y);
        const uint8_t bits = uint8_t((ok(a, b, c) ? 1 : 0) | (ok(c, d, a) ? 2 : 0));
        emit[size_t(y) * size_t(qw) + size_t(x)] = bits;
        row_count[size_t(y)] += size_t(bits & 1) + size_t(bits >> 1);
      }
    }
  });
  mesh.triangles.resize(prefix(row_count));
  parallel_for(size_t(qh), kRowGrain, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y) {
      size_t t = row_count[size_t(y)];
      for (int x = 0; x < qw; ++x) {
        const uint8_t bits = emit[size_t(y) * size_t(qw) + size_t(x)];
        const uint32_t a = vertex[s.index(x, y)], b = vertex[s.index(x, y + 1)], c = vertex[s.index(x + 1, y + 1)],
                       d = vertex[s.index(x + 1, y)];
        if (bits & 1) mesh.triangles[t++] = uvec3(a, b, c);
        if (bits & 2) mesh.triangles[t++] = uvec3(c, d, a);
      }
    }
  });
  return mesh;
}

Camera half_pixel_offset_camera(const Camera& c) {
  Camera h = c;
  h.width = c.width + 1;
  h.height = c.height + 1;
  // Same focal length in pixels: tan(vfov'/2) = (height + 1) / 2 / f.
  const double f = focal_length_px(c);
  h.vfov_deg = float(2.0 * std::atan(0.5 * double(h.height) / f) * 180.0 / 3.14159265358979323846);
  return h;
}

namespace {

// Per pixel corner: up to four vertices and, for the four pixels around it, which one
// each uses. Slot k is the pixel that sees this corner as its c_k: 0 = (i, j),
// 1 = (i, j−1), 2 = (i−1, j−1), 3 = (i−1, j).
struct CornerVertices {
  std::array<vec3, 4> position;
  std::array<uint8_t, 4> use{};  // local vertex index per slot (unused slots: 0)
  uint8_t count = 0;
  uint8_t fitted = 0;  // slots using a tangent-plane vertex
  uint8_t from_h = 0;  // slots using H's sample
};

// Corner depth on the sample's tangent plane along the ray through `corner`, clamped to
// kMaxCornerDepthOffset footprints from the sample's depth.
vec3 plane_corner(const Camera& cam, vec2 corner, const Samples& s, size_t k) {
  const vec3 p = s.points[k], n = s.normals[k];
  const float d = s.depth[k];
  const Ray r = ray_through(cam, corner);
  const float limit = kMaxCornerDepthOffset * d / s.focal;
  float depth = d;
  const float denom = glm::dot(n, r.dir);
  if (std::abs(denom) > 1e-8f) {
    const float t = glm::dot(n, p - r.origin) / denom;
    const float dc = t * glm::dot(r.dir, camera_forward(cam));
    if (std::isfinite(dc) && dc > 0.0f) depth = std::clamp(dc, d - limit, d + limit);
  }
  return unproject(cam, corner, depth);
}

CornerVertices corner_vertices(const Samples& s, const DepthImage& offset, const Camera& cam, int i, int j) {
  CornerVertices out;
  const int px[4] = {i, i, i - 1, i - 1}, py[4] = {j, j - 1, j - 1, j};
  std::array<int, 4> parent{0, 1, 2, 3};
  std::array<size_t, 4> k{};
  std::array<bool, 4> has{};
  for (int m = 0; m < 4; ++m) {
    has[m] = s.has(px[m], py[m]);
    if (has[m]) k[m] = s.index(px[m], py[m]);
  }
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a];
    return a;
  };
  // Edge neighbours around the corner: 0–1 and 2–3 share a vertical edge, 1–2 and 3–0 a
  // horizontal one.
  constexpr int kEdges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (const auto& e : kEdges) {
    const int a = e[0], b = e[1];
    if (has[a] && has[b] && continuous(s, k[a], k[b])) {
      const int ra = find(a), rb = find(b);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  // H's sample at this corner (its pixel (i, j) center is the corner).
  const bool h_valid = offset.triangle.at(i, j) != kNoTriangle;
  const vec3 h = h_valid ? sample_point(offset, i, j) : vec3(0.0f);
  int h_vertex = -1;
  const vec2 corner{float(i), float(j)};
  for (int root = 0; root < 4; ++root) {
    if (!has[root] || find(root) != root) continue;
    // H's sample must be on every member's surface (one member is not enough: it could be
    // off another member's tangent plane, bending that member's quad).
    bool accepts_h = h_valid;
    for (int m = 0; m < 4 && accepts_h; ++m)
      if (has[m] && find(m) == root && !same_surface(s.points[k[m]], s.normals[k[m]], s.depth[k[m]], s.focal, h))
        accepts_h = false;
    int v;
    if (accepts_h) {
      if (h_vertex < 0) {
        h_vertex = out.count++;
        out.position[size_t(h_vertex)] = h;
      }
      v = h_vertex;
    } else {
      vec3 sum(0.0f);
      int members = 0;
      for (int m = 0; m < 4; ++m)
        if (has[m] && find(m) == root) {
          sum += plane_corner(cam, corner, s, k[m]);
          ++members;
        }
      v = out.count++;
      out.position[size_t(v)] = sum / float(members);
    }
    for (int m = 0; m < 4; ++m) {
      if (!has[m] || find(m) != root) continue;
      out.use[size_t(m)] = uint8_t(v);
      (accepts_h ? out.from_h : out.fitted)++;
    }
  }
  return out;
}

}  // namespace

Mesh reconstruct_hybrid(const DepthImage& image, const DepthImage& offset, HybridStats* stats, bool merge_planar_runs) {
  const Samples s = gather(image);
  assert(offset.triangle.width() == s.width + 1 && offset.triangle.height() == s.height + 1);
  const Camera& cam = image.camera;
  const int cw = s.width + 1, ch = s.height + 1;
  std::vector<CornerVertices> corners(size_t(cw) * size_t(ch));
  std::vector<size_t> row_vertices(size_t(ch), 0);
  parallel_for(size_t(ch), kRowGrain, [&](size_t j0, size_t j1) {
    for (int j = int(j0); j < int(j1); ++j)
      for (int i = 0; i < cw; ++i) {
        CornerVertices& c = corners[size_t(j) * size_t(cw) + size_t(i)];
        c = corner_vertices(s, offset, cam, i, j);
        row_vertices[size_t(j)] += c.count;
      }
  });
  Mesh mesh;
  mesh.positions.resize(prefix(row_vertices));
  // Global id of the first vertex of every corner, and the vertices themselves.
  std::vector<uint32_t> first(corners.size(), 0);
  parallel_for(size_t(ch), kRowGrain, [&](size_t j0, size_t j1) {
    for (size_t j = j0; j < j1; ++j) {
      size_t v = row_vertices[j];
      for (size_t i = 0; i < size_t(cw); ++i) {
        const CornerVertices& c = corners[j * size_t(cw) + i];
        first[j * size_t(cw) + i] = uint32_t(v);
        for (int m = 0; m < c.count; ++m) mesh.positions[v++] = c.position[size_t(m)];
      }
    }
  });
  auto corner_id = [&](int i, int j, int slot) {
    const size_t c = size_t(j) * size_t(cw) + size_t(i);
    return first[c] + corners[c].use[size_t(slot)];
  };
  // extends[k]: sample k's quad joins the planar run of its left neighbour (merge only).
  std::vector<uint8_t> extends(s.valid.size(), 0);
  std::vector<size_t> row_quads(size_t(s.height), 0);
  parallel_for(size_t(s.height), kRowGrain, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y) {
      size_t start = 0;  // sample of the current run's first quad
      bool open = false;
      for (int x = 0; x < s.width; ++x) {
        const size_t k = s.index(x, y);
        if (!s.valid[k]) {
          open = false;
          continue;
        }
        auto on_plane = [&](uint32_t v) {
          const size_t r = start;
          return std::abs(glm::dot(s.normals[r], mesh.positions[v] - s.points[r])) <=
                 kMergeTolerance * s.depth[r] / s.focal;
        };
        const bool joins = merge_planar_runs && open && corner_id(x, y, 0) == corner_id(x, y, 3) &&
                           corner_id(x, y + 1, 1) == corner_id(x, y + 1, 2) && on_plane(corner_id(x + 1, y + 1, 2)) &&
                           on_plane(corner_id(x + 1, y, 3));
        if (joins) {
          extends[k] = 1;
          continue;
        }
        ++row_quads[size_t(y)];
        start = k;
        // A run starts only where the quad itself lies on its sample's plane.
        open = merge_planar_runs && on_plane(corner_id(x, y, 0)) && on_plane(corner_id(x, y + 1, 1)) &&
               on_plane(corner_id(x + 1, y + 1, 2)) && on_plane(corner_id(x + 1, y, 3));
      }
    }
  });
  const size_t quads = prefix(row_quads);
  mesh.triangles.resize(2 * quads);
  // Two triangles per run (one sample's quad or a planar run of them), row-major.
  parallel_for(size_t(s.height), kRowGrain, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y) {
      size_t t = 2 * row_quads[size_t(y)];
      for (int x = 0; x < s.width; ++x) {
        if (!s.valid[s.index(x, y)] || extends[s.index(x, y)]) continue;
        int end = x;  // last quad of the run
        while (end + 1 < s.width && extends[s.index(end + 1, y)]) ++end;
        const uint32_t c0 = corner_id(x, y, 0), c1 = corner_id(x, y + 1, 1), c2 = corner_id(end + 1, y + 1, 2),
                       c3 = corner_id(end + 1, y, 3);
        mesh.triangles[t++] = uvec3(c0, c1, c2);
        mesh.triangles[t++] = uvec3(c2, c3, c0);
      }
    }
  });
  size_t samples = 0;
  for (uint8_t v : s.valid) samples += v;
  if (stats) {
    *stats = {};
    stats->samples = samples;
    stats->quads = quads;
    stats->vertices = mesh.positions.size();
    for (const CornerVertices& c : corners) {
      stats->corners_from_h += c.from_h;
      stats->corners_fitted += c.fitted;
    }
  }
  return mesh;
}

Scene reconstruction_scene(std::span<const Mesh> meshes, const std::string& name) {
  Scene scene;
  scene.name = name;
  Material grey;
  grey.name = "reconstruction";
  grey.diffuse = vec3(0.5f);
  const uint32_t material = add_material(scene, grey);
  for (size_t i = 0; i < meshes.size(); ++i) {
    if (meshes[i].triangles.empty()) continue;
    add_object(scene, meshes[i], "mesh" + std::to_string(i), material);
  }
  return scene;
}

}  // namespace proxima
