// Synthetic calibrated photographs (Funkhouser, section 2: the GIBR system's input is a
// polygonal model plus photographs calibrated with camera viewpoints) and the camera file
// for real ones.
#include "proxima/gibr/photo_set.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include <nlohmann/json.hpp>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/gibr/lens.h"
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
    if (o.backoff > 0.0) {
      float back = float(o.backoff);
      for (int halved = 0; back > 0.0f && rays.occluded(Ray{pos, -f, 0.0f, back + 0.05f}); ++halved)
        back = halved < 4 ? 0.5f * back : 0.0f;
      pos -= back * f;
    }
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

namespace {

// Bilinear sample of pixel position (px, py) (pixel centers at +0.5); false outside the image.
bool bilinear(const ImageF& img, double px, double py, vec3& out) {
  const double sx = px - 0.5, sy = py - 0.5;
  if (!(sx >= -0.5 && sy >= -0.5 && sx <= img.width() - 0.5 && sy <= img.height() - 0.5)) return false;
  const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
  const double fx = sx - x0, fy = sy - y0;
  out = vec3(0.0f);
  for (int k = 0; k < 4; ++k) {
    const int x = std::clamp(x0 + (k & 1), 0, img.width() - 1), y = std::clamp(y0 + (k >> 1), 0, img.height() - 1);
    const double w = ((k & 1) ? fx : 1.0 - fx) * ((k >> 1) ? fy : 1.0 - fy);
    for (int c = 0; c < 3; ++c) out[c] += float(w) * img.at(x, y, c);
  }
  return true;
}

// Every pixel of the result sampled from `image` at the position `source` gives (false: black).
template <typename F>
ImageF resample(const ImageF& image, F&& source, ImageU8* valid) {
  ImageF out(image.width(), image.height(), 3, 0.0f);
  if (valid) *valid = ImageU8(image.width(), image.height(), 1, 0);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const glm::dvec2 s = source(x + 0.5, y + 0.5);
      vec3 c;
      if (!bilinear(image, s.x, s.y, c)) continue;
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
      if (valid) valid->at(x, y) = 1;
    }
  return out;
}

}  // namespace

ImageF undistort_photo(const ImageF& image, const Camera& camera, double k1, double k2, ImageU8* valid) {
  const Lens lens{k1, k2};
  return resample(image, [&](double px, double py) { return distort_pixel(camera, lens, {px, py}); }, valid);
}

ImageF distort_photo(const ImageF& image, const Camera& camera, double k1, double k2) {
  const Lens lens{k1, k2};
  return resample(image, [&](double px, double py) { return undistort_pixel(camera, lens, {px, py}); }, nullptr);
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
    if (p.k1 != 0.0 || p.k2 != 0.0) {
      j["photos"].back()["k1"] = p.k1;
      j["photos"].back()["k2"] = p.k2;
    }
    if (p.exposure != 1.0) j["photos"].back()["exposure"] = p.exposure;
  }
  write_text_file(path, j.dump(1) + "\n");
}

namespace {

// The optional k1, k2 and exposure of one photograph: finite, |k| ≤ 1, the distortion
// monotonic (r (1 + k1 r² + k2 r⁴) increasing) out to the image corners, exposure > 0.
void read_lens(const nlohmann::json& p, CalibratedPhoto& c, const std::filesystem::path& path) {
  c.k1 = p.value("k1", 0.0);
  c.k2 = p.value("k2", 0.0);
  c.exposure = p.value("exposure", 1.0);
  const std::string where = "camera file " + path.string() + ": photograph '" + c.image + "': ";
  if (!std::isfinite(c.k1) || !std::isfinite(c.k2) || std::abs(c.k1) > 1.0 || std::abs(c.k2) > 1.0)
    fail_input(where + "k1 and k2 must be finite numbers in [-1, 1]");
  if (!std::isfinite(c.exposure) || !(c.exposure > 0.0)) fail_input(where + "exposure must be a number > 0");
  const double f = focal_length_px(c.camera);
  const double rmax2 = (0.25 * c.camera.width * c.camera.width + 0.25 * c.camera.height * c.camera.height) / (f * f);
  // d/dr [r (1 + k1 r² + k2 r⁴)] = 1 + 3 k1 r² + 5 k2 r⁴ > 0 on [0, rmax].
  for (int s = 0; s <= 64; ++s) {
    const double r2 = rmax2 * s / 64.0;
    if (!(1.0 + 3.0 * c.k1 * r2 + 5.0 * c.k2 * r2 * r2 > 0.0))
      fail_input(where + "k1, k2 fold the image (distortion not monotonic out to the corners)");
  }
}

// An image dimension: a JSON integer in 1..65536 (a real number or a huge value would not
// convert to int safely).
int image_size(const nlohmann::json& v, const std::string& where) {
  if (!v.is_number_integer() || v.get<std::int64_t>() < 1 || v.get<std::int64_t>() > 65536 ||
      (v.is_number_unsigned() && v.get<std::uint64_t>() > 65536))
    fail_input(where + "width and height must be integers in 1..65536");
  return int(v.get<std::int64_t>());
}

}  // namespace

std::vector<CalibratedPhoto> read_camera_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail_input("camera file " + path.string() + ": cannot be read");
  std::vector<CalibratedPhoto> out;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.value("format", "") != "proxima-cameras" || j.value("version", nlohmann::json(0)) != 1)
      fail_input("camera file " + path.string() + ": not a proxima-cameras version 1 file");
    for (const auto& p : j.at("photos")) {
      CalibratedPhoto c;
      c.image = p.at("image").get<std::string>();
      const std::string where = "camera file " + path.string() + ": ";
      c.camera.width = image_size(p.at("width"), where);
      c.camera.height = image_size(p.at("height"), where);
      c.camera.vfov_deg = p.at("vfov_deg").get<float>();
      const auto& pos = p.at("position");
      const auto& q = p.at("orientation");
      if (pos.size() != 3 || q.size() != 4) fail_input("camera file " + path.string() + ": bad position/orientation");
      c.camera.position = vec3(pos[0].get<float>(), pos[1].get<float>(), pos[2].get<float>());
      c.camera.orientation = glm::normalize(quat(q[0].get<float>(), q[1].get<float>(), q[2].get<float>(), q[3].get<float>()));
      c.camera.near = p.value("near", 0.01f);
      c.camera.far = p.value("far", 1000.0f);
      validate_camera(c.camera, ("camera file " + path.string()).c_str());
      read_lens(p, c, path);
      out.push_back(std::move(c));
    }
  } catch (const nlohmann::json::exception& e) {
    fail_input("camera file " + path.string() + ": " + e.what());
  }
  return out;
}

}  // namespace proxima::gibr
