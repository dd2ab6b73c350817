#include "command.h"

#include <iostream>
#include <system_error>

#include "proxima/core/error.h"
#include "proxima/core/limits.h"

namespace proxima::cli {

namespace {
std::vector<std::string> g_command_line;
}

void add_limit_flags(CLI::App* app) {
  auto setter = [](uint64_t Limits::*field, const char* flag) {
    return [field, flag](uint64_t v) {
      if (v == 0) throw CLI::ValidationError(flag, "must be positive");
      try {
        Limits l = limits();  // keeps the other limit (environment or default)
        l.*field = v;
        set_limits(l);
      } catch (const InputError& e) {  // a malformed PROXIMA_MAX_* variable
        throw CLI::ValidationError(flag, e.what());
      }
    };
  };
  app->add_option_function<uint64_t>("--max-triangles", setter(&Limits::max_triangles, "--max-triangles"),
                                     "refuse scenes with more triangles (default 50000000, env PROXIMA_MAX_TRIANGLES)");
  app->add_option_function<uint64_t>("--max-memory-mb", setter(&Limits::max_memory_mb, "--max-memory-mb"),
                                     "refuse scenes/images estimated to need more MiB (default 3/4 of RAM, env "
                                     "PROXIMA_MAX_MEMORY_MB)");
}

void add_scene_flag(CLI::App* app, CommonOptions& o, const std::string& default_scene) {
  o.scene = default_scene;
  app->add_option("--scene", o.scene, "built-in scene name (see `proxima scenes`), .json scene file, or mesh file")
      ->capture_default_str();
  add_limit_flags(app);
}

void add_size_flags(CLI::App* app, CommonOptions& o) {
  app->add_option("--width", o.width, "image width in pixels")->capture_default_str();
  app->add_option("--height", o.height, "image height in pixels")->capture_default_str();
}

void add_threads_flag(CLI::App* app, CommonOptions& o) {
  app->add_option("--threads", o.threads, "worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
}

void add_seed_flag(CLI::App* app, CommonOptions& o) {
  app->add_option("--seed", o.seed, "random seed for every sampled quantity")->capture_default_str();
}

void add_out_flag(CLI::App* app, CommonOptions& o, bool required) {
  auto* opt = app->add_option("--out", o.out, "output directory (created if missing)");
  if (required) opt->required();
  else opt->capture_default_str();
}

void add_camera_flags(CLI::App* app, CameraChoice& choice) {
  auto* cam = app->add_option("--camera", choice.camera, "scene camera, by index or name (default: the first)");
  auto* path = app->add_option("--path", choice.path, "camera path, by index or name");
  app->add_option("--frame", choice.frame, "frame on the camera path (0-based)")->needs(path);
  cam->excludes(path);
}

namespace {

// Index (all digits) or name lookup; −1 if absent.
template <typename T, typename NameOf>
int find_by_index_or_name(const std::vector<T>& items, const std::string& key, NameOf name_of) {
  if (!key.empty() && key.find_first_not_of("0123456789") == std::string::npos) {
    size_t i = std::stoul(key);
    return i < items.size() ? int(i) : -1;
  }
  for (size_t i = 0; i < items.size(); ++i)
    if (name_of(items[i]) == key) return int(i);
  return -1;
}

}  // namespace

Camera pick_camera(const Scene& scene, const CameraChoice& choice, int width, int height) {
  Camera cam;
  if (!choice.path.empty()) {
    int p = find_by_index_or_name(scene.camera_paths, choice.path, [](const CameraPath& c) { return c.name; });
    if (p < 0)
      fail_input("--path: scene '" + scene.name + "' has no camera path '" + choice.path + "' (" +
                 std::to_string(scene.camera_paths.size()) + " paths)");
    const CameraPath& path = scene.camera_paths[size_t(p)];
    if (choice.frame < 0 || choice.frame >= path.frames)
      fail_input("--frame: " + std::to_string(choice.frame) + " is outside path '" + path.name + "' (0.." +
                 std::to_string(path.frames - 1) + ")");
    Bounds3 b = scene_bounds(scene);
    cam = camera_at_time(path, frame_time(path, choice.frame), width, height, 0.01f,
                         std::max(10.0f, 4.0f * b.diagonal()));
  } else if (!scene.cameras.empty()) {
    int c = choice.camera.empty()
                ? 0
                : find_by_index_or_name(scene.cameras, choice.camera, [](const NamedCamera& n) { return n.name; });
    if (c < 0)
      fail_input("--camera: scene '" + scene.name + "' has no camera '" + choice.camera + "' (" +
                 std::to_string(scene.cameras.size()) + " cameras)");
    cam = scene.cameras[size_t(c)].camera;
  } else {
    if (!choice.camera.empty()) fail_input("--camera: scene '" + scene.name + "' has no cameras");
    // No camera in the file: look at the bounds from the front (+Z), fitting them in view.
    Bounds3 b = scene_bounds(scene);
    float r = 0.5f * b.diagonal();
    vec3 c = b.center();
    // Clip distances scale with the scene (r > 0: sanitized scenes have a triangle of
    // non-zero area), so micrometer-sized models are not clipped away.
    cam = look_at(c + vec3(0.0f, 0.25f * r, 2.5f * r), c, {0, 1, 0}, 45.0f, width, height, 0.01f * r, 10.0f * r);
  }
  cam.width = width;
  cam.height = height;
  validate_camera(cam, "--width/--height");
  return cam;
}

std::filesystem::path prepare_out_dir(const std::string& out) {
  std::filesystem::path dir(out);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    fail_input("--out: cannot create directory " + out + (ec ? ": " + ec.message() : ""));
  return dir;
}

const std::vector<std::string>& command_line() { return g_command_line; }

void set_command_line(int argc, char** argv) { g_command_line.assign(argv, argv + argc); }

void publish_results(const std::filesystem::path& out_dir, const Results& results) {
  write_results_json(out_dir / "results.json", results);
  for (const Table& t : results.tables) std::cout << markdown_table(t) << "\n";
  std::cout << "results: " << (out_dir / "results.json").string() << "\n";
}

}  // namespace proxima::cli
