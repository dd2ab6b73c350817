// Synthetic calibrated photographs (Funkhouser, section 2: the GIBR system's input is a
// polygonal model plus photographs calibrated with camera viewpoints) and the camera file
// for real ones.
#include "proxima/gibr/photo_set.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::gibr {

namespace {

// Checker (8 × 8 cells per repeat) times value noise per texture pixel, tinted per channel.
ImageF make_texture(int size, uint64_t seed) {
  ImageF img(size, size, 3);
  Pcg32 rng(seed, 17);
  const vec3 tint(0.85f + 0.3f * rng.next_float(), 0.85f + 0.3f * rng.next_float(), 0.85f + 0.3f * rng.next_float());
  const int cell = std::max(1, size / 8);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float checker = ((x / cell + y / cell) % 2) ? 1.0f : 0.6f;
      for (int c = 0; c < 3; ++c) {
        const float noise = 0.55f + 0.45f * rng.next_float();
        img.at(x, y, c) = std::min(1.0f, checker * noise * tint[c]);
      }
    }
  return img;
}

}  // namespace

Scene make_photo_scene(const Scene& model, const PhotoSceneOptions& options) {
  if (!(options.period > 0.0) || options.texture_size < 8 || options.texture_size > 4096)
    fail_input("photo scene: period must be > 0 and texture size in 8..4096");
  Scene s = model;
  s.textures.clear();
  for (size_t m = 0; m < s.materials.size(); ++m) {
    Texture t;
    t.name = "gibr_noise_" + std::to_string(m);
    t.image = make_texture(options.texture_size, derive_seed(options.seed, m));
    s.textures.push_back(std::move(t));
    s.materials[m].diffuse_texture = int(m);
  }
  const float inv = float(1.0 / options.period);
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const vec3 p = s.positions[i], n = glm::abs(s.normals[i]);
    if (n.y >= n.x && n.y >= n.z) s.uvs[i] = vec2(p.x, p.z) * inv;
    else if (n.x >= n.z) s.uvs[i] = vec2(p.z, p.y) * inv;
    else s.uvs[i] = vec2(p.x, p.y) * inv;
  }
  return s;
}

std::vector<Camera> photo_poses(const RayScene& rays, const CameraPath& path, const PhotoPoseOptions& o, float near,
                                float far) {
  require_at_least(o.count, 1, "--photos");
  std::vector<Camera> out;
  const float t0 = path.keys.front().time, t1 = path.keys.back().time;
  for (int i = 0; i < o.count; ++i) {
    Pcg32 rng(derive_seed(o.seed, uint64_t(i), 0x9b07), 3);
    auto uniform = [&](double a, double b) { return float(a + (b - a) * rng.next_float()); };
    const float t = t0 + (t1 - t0) * rng.next_float();
    const Camera base = camera_at_time(path, t, o.width, o.height, near, far);
    vec3 pos = base.position + vec3(uniform(-o.jitter, o.jitter), uniform(-o.jitter, o.jitter),
                                     uniform(-o.jitter, o.jitter));
    // Keep the photo in the path's free space: the jitter must not cross a surface.
    const vec3 d = pos - base.position;
    const float len = glm::length(d);
    if (len > 0.0f) {
      Ray r{base.position, d / len, 0.0f, len + 0.05f};
      if (rays.occluded(r)) pos = base.position;
    }
    const vec3 f = camera_forward(base);
    const float yaw = glm::radians(uniform(-o.yaw_deg, o.yaw_deg));
    const float pitch = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)) + glm::radians(uniform(-o.pitch_deg, o.pitch_deg)),
                                   -1.3f, 1.3f);
    float heading = std::atan2(f.x, f.z) + yaw;
    const vec3 dir(std::cos(pitch) * std::sin(heading), std::sin(pitch), std::cos(pitch) * std::cos(heading));
    out.push_back(look_at(pos, pos + dir, {0, 1, 0}, base.vfov_deg, o.width, o.height, near, far));
  }
  return out;
}

std::vector<Camera> offpath_poses(const RayScene& rays, const CameraPath& path, int count, int width, int height,
                                  double offset, float near, float far) {
  std::vector<Camera> out;
  const float t0 = path.keys.front().time, t1 = path.keys.back().time;
  for (int i = 0; i < count; ++i) {
    const float t = count == 1 ? t0 : t0 + (t1 - t0) * float(i) / float(count - 1);
    Camera c = camera_at_time(path, t, width, height, near, far);
    const float sx = (i % 2 == 0) ? 1.0f : -1.0f, sy = ((i / 2) % 2 == 0) ? 1.0f : -1.0f;
    const vec3 dir = glm::normalize(sx * camera_right(c) + 0.5f * sy * camera_up(c));
    float len = float(offset) * std::sqrt(1.25f);
    // Stay in the path's free space: shorten the step until it crosses no surface.
    for (int halved = 0; len > 0.0f && rays.occluded(Ray{c.position, dir, 0.0f, len + 0.05f}); ++halved)
      len = halved < 4 ? 0.5f * len : 0.0f;
    c.position += len * dir;
    out.push_back(c);
  }
  return out;
}

ReferenceOptions photo_render_options(int supersample, uint64_t seed) {
  ReferenceOptions ro;
  ro.supersample = supersample;
  ro.area_light_samples = 1;
  ro.max_bounces = 0;
  ro.seed = seed;
  return ro;
}

ImageF render_photo(const Scene& scene, const RayScene& rays, const Camera& camera, int supersample, uint64_t seed) {
  return render_reference(scene, rays, camera, photo_render_options(supersample, seed));
}

void write_camera_file(const std::filesystem::path& path, const std::vector<CalibratedPhoto>& photos) {
  nlohmann::json j;
  j["format"] = "proxima-cameras";
  j["version"] = 1;
  j["photos"] = nlohmann::json::array();
  for (const CalibratedPhoto& p : photos) {
    const Camera& c = p.camera;
    j["photos"].push_back({{"image", p.image},
                           {"width", c.width},
                           {"height", c.height},
                           {"vfov_deg", c.vfov_deg},
                           {"position", {c.position.x, c.position.y, c.position.z}},
                           {"orientation", {c.orientation.w, c.orientation.x, c.orientation.y, c.orientation.z}},
                           {"near", c.near},
                           {"far", c.far}});
  }
  write_text_file(path, j.dump(1) + "\n");
}

std::vector<CalibratedPhoto> read_camera_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail_input("camera file " + path.string() + ": cannot be read");
  std::vector<CalibratedPhoto> out;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.value("format", "") != "proxima-cameras" || j.value("version", 0) != 1)
      fail_input("camera file " + path.string() + ": not a proxima-cameras version 1 file");
    for (const auto& p : j.at("photos")) {
      CalibratedPhoto c;
      c.image = p.at("image").get<std::string>();
      c.camera.width = p.at("width").get<int>();
      c.camera.height = p.at("height").get<int>();
      c.camera.vfov_deg = p.at("vfov_deg").get<float>();
      const auto& pos = p.at("position");
      const auto& q = p.at("orientation");
      if (pos.size() != 3 || q.size() != 4) fail_input("camera file " + path.string() + ": bad position/orientation");
      c.camera.position = vec3(pos[0].get<float>(), pos[1].get<float>(), pos[2].get<float>());
      c.camera.orientation = glm::normalize(quat(q[0].get<float>(), q[1].get<float>(), q[2].get<float>(), q[3].get<float>()));
      c.camera.near = p.value("near", 0.01f);
      c.camera.far = p.value("far", 1000.0f);
      validate_camera(c.camera, ("camera file " + path.string()).c_str());
      out.push_back(std::move(c));
    }
  } catch (const nlohmann::json::exception& e) {
    fail_input("camera file " + path.string() + ": " + e.what());
  }
  return out;
}

}  // namespace proxima::gibr
