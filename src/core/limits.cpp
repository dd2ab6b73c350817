#include "proxima/core/limits.h"

#include <unistd.h>

#include <charconv>
#include <cstdlib>
#include <mutex>
#include <string_view>

#include "proxima/core/camera.h"
#include "proxima/core/error.h"

namespace proxima {
namespace {

// Per triangle: indices, material and object ids (20 B) plus Embree's BVH (~64 B) plus one
// transient copy while loading; per vertex: position, normal, uv (32 B) twice.
constexpr uint64_t kBytesPerTriangle = 128;
constexpr uint64_t kBytesPerVertex = 64;

uint64_t env_or(const char* name, uint64_t fallback) {
  const char* s = std::getenv(name);
  if (s == nullptr) return fallback;
  uint64_t v = 0;
  const std::string_view text(s);
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v == 0)
    fail_input(std::string(name) + ": must be a positive integer, not '" + s + "'");
  return v;
}

uint64_t default_memory_mb() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 16384;
  return uint64_t(pages) / 4 * 3 * uint64_t(page) >> 20;
}

std::mutex g_mutex;
bool g_initialized = false;
Limits g_limits;

}  // namespace

Limits limits() {
  std::lock_guard lock(g_mutex);
  if (!g_initialized) {
    g_limits.max_triangles = env_or("PROXIMA_MAX_TRIANGLES", g_limits.max_triangles);
    g_limits.max_memory_mb = env_or("PROXIMA_MAX_MEMORY_MB", default_memory_mb());
    g_initialized = true;
  }
  return g_limits;
}

void set_limits(const Limits& l) {
  Limits resolved = l;
  if (resolved.max_memory_mb == 0) resolved.max_memory_mb = default_memory_mb();
  std::lock_guard lock(g_mutex);
  g_limits = resolved;
  g_initialized = true;
}

uint64_t geometry_bytes(uint64_t triangles, uint64_t vertices) {
  return triangles * kBytesPerTriangle + vertices * kBytesPerVertex;
}

std::string geometry_budget_error(uint64_t triangles, uint64_t vertices) {
  const Limits l = limits();
  if (triangles > l.max_triangles)
    return std::to_string(triangles) + " triangles exceed the limit of " + std::to_string(l.max_triangles) +
           " (--max-triangles, PROXIMA_MAX_TRIANGLES)";
  const uint64_t mb = geometry_bytes(triangles, vertices) >> 20;
  if (mb > l.max_memory_mb)
    return std::to_string(triangles) + " triangles and " + std::to_string(vertices) + " vertices need about " +
           std::to_string(mb) + " MiB, more than the limit of " + std::to_string(l.max_memory_mb) +
           " MiB (--max-memory-mb, PROXIMA_MAX_MEMORY_MB)";
  return {};
}

void check_geometry_budget(const std::string& what, uint64_t triangles, uint64_t vertices) {
  const std::string error = geometry_budget_error(triangles, vertices);
  if (!error.empty()) fail_input(what + ": " + error);
}

void check_image_budget(const std::string& what, uint64_t width, uint64_t height, uint64_t channels) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width > uint64_t(kMaxImageSide) || height > uint64_t(kMaxImageSide))
    fail_input(what + ": image of " + size + " pixels exceeds the maximum side " + std::to_string(kMaxImageSide));
  const uint64_t mb = width * height * channels * sizeof(float) >> 20;
  const Limits l = limits();
  if (mb > l.max_memory_mb)
    fail_input(what + ": image of " + size + " pixels needs about " + std::to_string(mb) +
               " MiB, more than the limit of " + std::to_string(l.max_memory_mb) +
               " MiB (--max-memory-mb, PROXIMA_MAX_MEMORY_MB)");
}

}  // namespace proxima
