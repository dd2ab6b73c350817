// Resource limits: bounds checked *before* large allocations, so a hostile or mistaken
// input (a scene file asking for 10^9 triangles, a glTF instancing one mesh a million
// times, a 100000² texture) fails with a one-line InputError (exit 2) instead of
// exhausting the machine. The image side limit is kMaxImageSide (core/camera.h).
#pragma once

#include <cstdint>
#include <string>

namespace proxima {

// Mesh files: the deepest node graph and JSON nesting accepted (glTF). assimp's glTF
// reader (rapidjson), node builder, post-processing and node destructor recurse once per
// level, so deeper files are refused before assimp sees them rather than overflowing
// the stack (docs/formats.md).
inline constexpr int kMaxNodeDepth = 1000;
inline constexpr int kMaxJsonNesting = 256;

// Mesh files: the most vertices one polygon may have. assimp triangulates an n-gon by ear
// clipping, superlinear in n (a 4096-gon took 1.4 s, a 1024-gon 0.1 s on the shared VM),
// so a file of a few huge faces would hang the import; triangles and quads are the norm.
inline constexpr int kMaxFaceVertices = 1024;

struct Limits {
  uint64_t max_triangles = 50'000'000;  // per scene, after import, instancing and generation
  uint64_t max_memory_mb = 0;           // estimated peak for one scene or image; 0 = ¾ of RAM
};

// The process-wide limits: the defaults above, overridden by the environment variables
// PROXIMA_MAX_TRIANGLES and PROXIMA_MAX_MEMORY_MB (read on first use), overridden by
// set_limits() (the --max-triangles / --max-memory-mb flags). max_memory_mb is resolved
// (never 0) in the returned value.
Limits limits();
void set_limits(const Limits& limits);

// Estimated peak bytes for a scene of `triangles` triangles and `vertices` vertices: the
// scene arrays, transient copies while loading and the BVH.
uint64_t geometry_bytes(uint64_t triangles, uint64_t vertices);

// "N triangles exceed the limit of M (--max-triangles, …)" when a scene of that size would
// hold more than max_triangles, or a message naming the memory when geometry_bytes()
// exceeds max_memory_mb; empty when it fits. Callers pass the scene's running totals
// including what they are about to add.
std::string geometry_budget_error(uint64_t triangles, uint64_t vertices);

// Throws InputError "`what`: <geometry_budget_error>" when the geometry does not fit.
void check_geometry_budget(const std::string& what, uint64_t triangles, uint64_t vertices);

// Throws InputError naming `what` when an image read from a file (`channels` floats per
// pixel) has a side above kMaxImageSide or would not fit in max_memory_mb. Call it with the
// header's size, before decoding.
void check_image_budget(const std::string& what, uint64_t width, uint64_t height, uint64_t channels);

}  // namespace proxima
