// Shared by the libFuzzer targets (one *_fuzz.cpp per input path, built by
// -DPROXIMA_FUZZ=ON with clang; scripts/fuzz.sh runs one). A target writes the input to a
// scratch file with the extension the reader dispatches on, runs the real code path,
// treats InputError as a normal outcome, and checks proxima's invariants on success. An
// invariant violation, any other exception, a sanitizer report or a leak is a finding.
//
// Adding a target for a new format: copy png_fuzz.cpp, call the reader, check its result,
// add seeds to scripts/fuzz_seeds.sh.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/image.h"
#include "proxima/core/image_io.h"
#include "proxima/core/limits.h"
#include "proxima/scene/scene.h"

#define FUZZ_CHECK(cond)                                                                   \
  do {                                                                                     \
    if (!(cond)) {                                                                         \
      std::fprintf(stderr, "fuzz invariant failed: %s (%s:%d)\n", #cond, __FILE__, __LINE__); \
      std::abort();                                                                        \
    }                                                                                      \
  } while (0)

namespace proxima::fuzz {

// Limits far below libFuzzer's 2 GB RSS limit, so oversized inputs exercise the limit
// checks (an InputError) instead of being reported as out-of-memory.
inline void init_limits() { set_limits({.max_triangles = 20'000, .max_memory_mb = 64}); }

// `data` written to <tmp>/proxima_fuzz_<pid>/input<ext> (per process: -jobs/-fork safe).
inline std::filesystem::path write_input(const uint8_t* data, size_t size, const std::string& ext) {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("proxima_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::filesystem::path path = dir / ("input" + ext);
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

// Runs `fn`; bad input (InputError) is an expected outcome, anything else propagates.
template <typename F>
void expect_input_errors_only(F fn) {
  try {
    fn();
  } catch (const InputError&) {
  }
}

inline bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What load_scene promises (scene.h, sanitize_scene) and the renderers rely on.
inline void check_scene(const Scene& s) {
  const size_t nv = s.positions.size(), nt = s.triangles.size();
  FUZZ_CHECK(nt > 0 && nt <= limits().max_triangles);
  FUZZ_CHECK(s.normals.size() == nv && s.uvs.size() == nv);
  FUZZ_CHECK(s.triangle_material.size() == nt && s.triangle_object.size() == nt);
  for (size_t i = 0; i < nv; ++i) {
    FUZZ_CHECK(finite(s.positions[i]) && finite(s.normals[i]));
    FUZZ_CHECK(std::isfinite(s.uvs[i].x) && std::isfinite(s.uvs[i].y));
  }
  for (size_t t = 0; t < nt; ++t) {
    FUZZ_CHECK(s.triangles[t].x < nv && s.triangles[t].y < nv && s.triangles[t].z < nv);
    FUZZ_CHECK(s.triangle_material[t] < s.materials.size());
    FUZZ_CHECK(s.triangle_object[t] < s.objects.size());
  }
  // Objects own contiguous, in-order triangle ranges that tile the triangle array.
  uint64_t next = 0;
  for (size_t o = 0; o < s.objects.size(); ++o) {
    const Object& obj = s.objects[o];
    FUZZ_CHECK(obj.first_triangle == next);
    next += obj.triangle_count;
    FUZZ_CHECK(next <= nt);
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t)
      FUZZ_CHECK(s.triangle_object[t] == o);
    FUZZ_CHECK(uint64_t(obj.first_vertex) + obj.vertex_count <= nv);
  }
  FUZZ_CHECK(next == nt);
  for (const Material& m : s.materials) {
    FUZZ_CHECK(m.specular >= 0.0f && m.specular <= 1.0f && m.gloss >= 0.0f && m.gloss <= 1.0f);
    FUZZ_CHECK(finite(m.diffuse) && finite(m.emission));
    FUZZ_CHECK(m.diffuse_texture >= -1 && m.diffuse_texture < int(s.textures.size()));
  }
  for (const Texture& t : s.textures) FUZZ_CHECK(!t.image.empty() && t.image.channels() == 3);
  for (const PointLight& l : s.point_lights) FUZZ_CHECK(finite(l.position) && finite(l.intensity));
  for (const AreaLight& l : s.area_lights) FUZZ_CHECK(l.area() > 0.0f && finite(l.radiance));
  for (const CameraPath& p : s.camera_paths) {
    FUZZ_CHECK(!p.keys.empty() && p.frames >= 1);
    for (size_t k = 1; k < p.keys.size(); ++k) FUZZ_CHECK(p.keys[k].time > p.keys[k - 1].time);
  }
}

// A decoded image: the size it claims, within the limits, 1..4 channels.
inline void check_image(const ImageF& img) {
  FUZZ_CHECK(img.width() > 0 && img.height() > 0 && img.channels() >= 1 && img.channels() <= 4);
  FUZZ_CHECK(img.data().size() == img.pixel_count() * size_t(img.channels()));
}

// One input of an 8-bit image reader (PNG, JPEG): read_image_linear either throws
// InputError or returns a well-formed 3-channel image of decoded sRGB values in [0, 1].
inline void read_8bit_image(const uint8_t* data, size_t size, const std::string& ext) {
  init_limits();
  const auto path = write_input(data, size, ext);
  expect_input_errors_only([&] {
    const ImageF img = read_image_linear(path, 3);
    check_image(img);
    FUZZ_CHECK(img.channels() == 3);
    for (float v : img.data()) FUZZ_CHECK(v >= 0.0f && v <= 1.0f);
  });
}

}  // namespace proxima::fuzz
