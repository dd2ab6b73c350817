// Scenes and cameras: load_scene, Scene (objects, editable materials, cameras, camera
// paths, geometry as read-only arrays), Camera.
#include <mutex>

#include "arrays.h"
#include "bindings.h"
#include "proxima/core/camera.h"
#include "proxima/core/limits.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/load.h"
#include "scene_handle.h"

namespace proxima::python {

namespace {

py::tuple to_tuple(vec3 v) { return py::make_tuple(v.x, v.y, v.z); }

py::array_t<float> matrix_array(const mat4& m) {
  py::array_t<float> a({4, 4});
  auto r = a.mutable_unchecked<2>();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r(i, j) = m[j][i];  // glm is column-major
  return a;
}

// A read-only array over the scene's own memory; the array keeps the scene alive.
template <typename T>
py::array scene_array(const std::shared_ptr<SceneHandle>& handle, const T* data, std::vector<py::ssize_t> shape) {
  py::array a(py::dtype::of<T>(), shape, {}, data, py::cast(handle));
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// One material of a scene, edited in place (renders that run meanwhile see the old values).
struct MaterialRef {
  std::shared_ptr<SceneHandle> scene;
  uint32_t index;

  const Material& get() const { return scene->scene().materials[index]; }
  template <typename Edit>
  void edit(Edit&& e) {
    py::gil_scoped_release release;
    const auto lock = scene->write_lock();
    e(scene->mutable_scene().materials[index]);
  }
};

float unit_interval(float v, const char* what) {
  if (!(v >= 0.0f && v <= 1.0f)) fail_input(std::string(what) + ": must be in [0, 1]");
  return v;
}

vec3 non_negative_color(py::handle obj, const char* what) {
  const vec3 c = to_vec3(obj, what);
  if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) fail_input(std::string(what) + ": must be ≥ 0");
  return c;
}

// `camera` as pick_camera's key: an index or a name; None = the scene's first camera.
std::string camera_key(py::handle key) {
  if (key.is_none()) return "";
  if (py::isinstance<py::int_>(key)) {
    const long long i = key.cast<long long>();
    if (i < 0) fail_input("--camera: index " + std::to_string(i) + " is negative");
    return std::to_string(i);
  }
  if (py::isinstance<py::str>(key)) return key.cast<std::string>();
  fail_input("--camera: expected a name or an index, got " + describe(key));
}

std::mutex g_limit_mutex;

std::shared_ptr<SceneHandle> load(const std::string& name_or_path, std::optional<uint64_t> max_triangles) {
  py::gil_scoped_release release;
  if (!max_triangles) return std::make_shared<SceneHandle>(load_scene(name_or_path));
  if (*max_triangles == 0) fail_input("max_triangles: must be positive");
  // The limit is process-wide: loads with their own limit take turns.
  const std::lock_guard lock(g_limit_mutex);
  const Limits before = limits();
  Limits l = before;
  l.max_triangles = *max_triangles;
  set_limits(l);
  try {
    auto handle = std::make_shared<SceneHandle>(load_scene(name_or_path));
    set_limits(before);
    return handle;
  } catch (...) {
    set_limits(before);
    throw;
  }
}

void bind_camera(py::module_& m) {
  py::class_<Camera>(m, "Camera",
                     "A pinhole camera. World space: right-handed, +Y up, meters; the camera looks down "
                     "its −Z axis. Images are height × width, row 0 on top.")
      .def(py::init([](py::handle position, py::handle target, py::handle up, float vfov_deg, int width, int height,
                       float near, float far) {
             Camera c = look_at(to_vec3(position, "Camera position"), to_vec3(target, "Camera target"),
                                to_vec3(up, "Camera up"), vfov_deg, width, height, near, far);
             validate_camera(c, "Camera");
             return c;
           }),
           py::arg("position"), py::arg("target"), py::arg("up") = py::make_tuple(0.0f, 1.0f, 0.0f),
           py::arg("vfov_deg") = 60.0f, py::arg("width") = 512, py::arg("height") = 512, py::arg("near") = 0.01f,
           py::arg("far") = 1000.0f,
           "Camera at `position` (m) looking at `target` (m); `up` need not be orthogonal to the view "
           "direction but not parallel to it. vfov_deg: full vertical field of view in degrees; width, "
           "height: pixels; near, far: clip distances along the view axis in meters.")
      .def_property(
          "position", [](const Camera& c) { return to_tuple(c.position); },
          [](Camera& c, py::handle v) { c.position = to_vec3(v, "position"); }, "World position (m), (x, y, z).")
      .def_property_readonly("forward", [](const Camera& c) { return to_tuple(camera_forward(c)); },
                             "Unit world direction of the view axis (−Z of the camera).")
      .def_property_readonly("right", [](const Camera& c) { return to_tuple(camera_right(c)); },
                             "Unit world direction of +X of the camera (image right).")
      .def_property_readonly("up", [](const Camera& c) { return to_tuple(camera_up(c)); },
                             "Unit world direction of +Y of the camera (image up).")
      .def_readwrite("vfov_deg", &Camera::vfov_deg, "Full vertical field of view, degrees, in (0, 180).")
      .def_readwrite("width", &Camera::width, "Image width, pixels.")
      .def_readwrite("height", &Camera::height, "Image height, pixels.")
      .def_readwrite("near", &Camera::near, "Near clip distance along the view axis, m.")
      .def_readwrite("far", &Camera::far, "Far clip distance along the view axis, m.")
      .def("view_matrix", [](const Camera& c) { return matrix_array(view_matrix(c)); },
           "World → camera 4×4 float32 matrix (OpenGL convention, acts on column vectors).")
      .def("projection_matrix", [](const Camera& c) { return matrix_array(projection_matrix(c)); },
           "Camera → clip 4×4 float32 matrix (OpenGL convention, clip z in [−w, w]).")
      .def("__repr__", [](const Camera& c) {
        const vec3 f = camera_forward(c);
        return "Camera(position=(" + std::to_string(c.position.x) + ", " + std::to_string(c.position.y) + ", " +
               std::to_string(c.position.z) + "), forward=(" + std::to_string(f.x) + ", " + std::to_string(f.y) +
               ", " + std::to_string(f.z) + "), vfov_deg=" + std::to_string(c.vfov_deg) + ", " +
               std::to_string(c.width) + "x" + std::to_string(c.height) + ")";
      });
}

void bind_scene_parts(py::module_& m) {
  py::class_<Object>(m, "SceneObject", "One object of a scene: a contiguous range of triangles and vertices.")
      .def_readonly("name", &Object::name)
      .def_readonly("first_triangle", &Object::first_triangle)
      .def_readonly("triangle_count", &Object::triangle_count)
      .def_readonly("first_vertex", &Object::first_vertex)
      .def_readonly("vertex_count", &Object::vertex_count)
      .def_property_readonly("animated", [](const Object& o) { return o.animation.animated(); })
      .def("__repr__", [](const Object& o) {
        return "SceneObject('" + o.name + "', " + std::to_string(o.triangle_count) + " triangles)";
      });
  py::class_<CameraPath>(m, "CameraPath", "A camera path of a scene: key frames sampled into `frames` frames.")
      .def_readonly("name", &CameraPath::name)
      .def_readonly("frames", &CameraPath::frames)
      .def_property_readonly("key_count", [](const CameraPath& p) { return p.keys.size(); })
      .def("frame_time", [](const CameraPath& p, int frame) { return frame_time(p, frame); }, py::arg("frame"),
           "Time of a frame, seconds (the clock of the scene's animations).")
      .def("__repr__", [](const CameraPath& p) {
        return "CameraPath('" + p.name + "', " + std::to_string(p.frames) + " frames)";
      });
  py::class_<MaterialRef>(m, "Material",
                          "A material of a scene, edited in place: later renders of the scene use the new "
                          "values (docs/shading.md).")
      .def_property_readonly("name", [](const MaterialRef& r) { return r.get().name; })
      .def_property_readonly("index", [](const MaterialRef& r) { return r.index; })
      .def_property(
          "diffuse", [](const MaterialRef& r) { return to_tuple(r.get().diffuse); },
          [](MaterialRef& r, py::handle v) {
            const vec3 c = non_negative_color(v, "diffuse");
            r.edit([&](Material& mat) { mat.diffuse = c; });
          },
          "Diffuse albedo, linear RGB ≥ 0 (multiplied by the texture when there is one).")
      .def_property(
          "specular", [](const MaterialRef& r) { return r.get().specular; },
          [](MaterialRef& r, float v) {
            unit_interval(v, "specular");
            r.edit([&](Material& mat) { mat.specular = v; });
          },
          "Specular weight s in [0, 1]: 0 = diffuse, 1 = perfect reflector.")
      .def_property(
          "gloss", [](const MaterialRef& r) { return r.get().gloss; },
          [](MaterialRef& r, float v) {
            unit_interval(v, "gloss");
            r.edit([&](Material& mat) { mat.gloss = v; });
          },
          "Gloss g in [0, 1]: 0 = mirror, 1 = widest lobe.")
      .def_property(
          "emission", [](const MaterialRef& r) { return to_tuple(r.get().emission); },
          [](MaterialRef& r, py::handle v) {
            const vec3 c = non_negative_color(v, "emission");
            r.edit([&](Material& mat) { mat.emission = c; });
          },
          "Emitted radiance, linear RGB ≥ 0.")
      .def_property_readonly("has_texture", [](const MaterialRef& r) { return r.get().diffuse_texture >= 0; })
      .def("__repr__", [](const MaterialRef& r) {
        const Material& mat = r.get();
        return "Material('" + mat.name + "', specular=" + std::to_string(mat.specular) +
               ", gloss=" + std::to_string(mat.gloss) + ")";
      });
}

void bind_scene_class(py::module_& m) {
  using H = std::shared_ptr<SceneHandle>;
  py::class_<SceneHandle, H>(m, "Scene",
                             "A loaded scene: triangles, objects, materials, lights, cameras and camera paths. "
                             "World space: right-handed, +Y up, meters. Its Embree BVH is built on first use "
                             "and kept.")
      .def_property_readonly("name", [](const SceneHandle& s) { return s.scene().name; })
      .def_property_readonly("triangle_count", [](const SceneHandle& s) { return s.scene().triangles.size(); })
      .def_property_readonly("vertex_count", [](const SceneHandle& s) { return s.scene().positions.size(); })
      .def_property_readonly("object_count", [](const SceneHandle& s) { return s.scene().objects.size(); })
      .def_property_readonly("objects", [](const SceneHandle& s) { return s.scene().objects; },
                             "The objects (a copy): names and triangle ranges.")
      .def_property_readonly(
          "materials",
          [](const H& s) {
            std::vector<MaterialRef> refs;
            for (uint32_t i = 0; i < s->scene().materials.size(); ++i) refs.push_back({s, i});
            return refs;
          },
          "The materials, editable in place (specular, gloss, diffuse, emission).")
      .def_property_readonly(
          "cameras",
          [](const SceneHandle& s) {
            std::vector<std::string> names;
            for (const auto& c : s.scene().cameras) names.push_back(c.name);
            return names;
          },
          "Names of the scene's cameras (camera(name_or_index) gives one).")
      .def_property_readonly("camera_paths", [](const SceneHandle& s) { return s.scene().camera_paths; },
                             "The camera paths (path_camera(path, frame) gives a frame's camera).")
      .def_property_readonly("animated", [](const SceneHandle& s) { return has_animation(s.scene()); })
      .def_property_readonly("dropped_degenerate", [](const SceneHandle& s) { return s.scene().dropped_degenerate; },
                             "Zero-area triangles dropped when the scene was loaded.")
      .def_property_readonly(
          "bounds",
          [](const SceneHandle& s) {
            const Bounds3 b = scene_bounds(s.scene());
            return py::make_tuple(to_tuple(b.min), to_tuple(b.max));
          },
          "World bounds ((xmin, ymin, zmin), (xmax, ymax, zmax)), m.")
      .def_property_readonly(
          "positions",
          [](const H& s) { return scene_array(s, reinterpret_cast<const float*>(s->scene().positions.data()), {py::ssize_t(s->scene().positions.size()), 3}); },
          "Vertex positions, V×3 float32, world space (m), rest pose; read-only view.")
      .def_property_readonly(
          "normals",
          [](const H& s) { return scene_array(s, reinterpret_cast<const float*>(s->scene().normals.data()), {py::ssize_t(s->scene().normals.size()), 3}); },
          "Unit vertex normals, V×3 float32, world space; read-only view.")
      .def_property_readonly(
          "triangles",
          [](const H& s) {
            return scene_array(s, reinterpret_cast<const uint32_t*>(s->scene().triangles.data()), {py::ssize_t(s->scene().triangles.size()), 3});
          },
          "Vertex indices, T×3 uint32, counter-clockwise seen from the front; read-only view. Row i is "
          "triangle id i.")
      .def_property_readonly(
          "triangle_object",
          [](const H& s) {
            return scene_array(s, s->scene().triangle_object.data(), {py::ssize_t(s->scene().triangle_object.size())});
          },
          "Object id of each triangle, T uint32; read-only view.")
      .def_property_readonly(
          "triangle_material",
          [](const H& s) {
            return scene_array(s, s->scene().triangle_material.data(),
                               {py::ssize_t(s->scene().triangle_material.size())});
          },
          "Material id of each triangle, T uint32; read-only view.")
      .def(
          "camera",
          [](const SceneHandle& s, py::handle key, int width, int height) {
            CameraChoice choice;
            choice.camera = camera_key(key);
            return pick_camera(s.scene(), choice, width, height);
          },
          py::arg("name_or_index") = py::none(), py::arg("width") = 512, py::arg("height") = 512,
          "A camera of the scene by name or index (None: the first; a scene without cameras is viewed "
          "from +Z, fitting its bounds) at width × height pixels.")
      .def(
          "path_camera",
          [](const SceneHandle& s, py::handle path, int frame, int width, int height) {
            CameraChoice choice;
            if (py::isinstance<py::int_>(path)) choice.path = std::to_string(path.cast<long long>());
            else if (py::isinstance<py::str>(path)) choice.path = path.cast<std::string>();
            else fail_input("--path: expected a name or an index, got " + describe(path));
            choice.frame = frame;
            return pick_camera(s.scene(), choice, width, height);
          },
          py::arg("path"), py::arg("frame"), py::arg("width") = 512, py::arg("height") = 512,
          "The camera of frame `frame` (0 .. frames − 1) of a camera path (name or index) at width × height "
          "pixels.")
      .def("__repr__", [](const SceneHandle& s) {
        return "Scene('" + s.scene().name + "', " + std::to_string(s.scene().triangles.size()) + " triangles, " +
               std::to_string(s.scene().objects.size()) + " objects)";
      });
}

}  // namespace

void bind_scene(py::module_& m) {
  bind_camera(m);
  bind_scene_parts(m);
  bind_scene_class(m);
  m.def("load_scene", &load, py::arg("name_or_path"), py::arg("max_triangles") = py::none(),
        "Loads a built-in scene by name (builtin_scenes()), a .json scene file or a mesh file (OBJ, glTF, "
        "PLY, …). max_triangles: refuse scenes with more triangles (default: the process limit, 50 million "
        "or PROXIMA_MAX_TRIANGLES). Raises FileNotFoundError for a missing file, ValueError for a bad one.");
  m.def(
      "builtin_scenes",
      [] {
        std::vector<std::pair<std::string, std::string>> out;
        for (const auto& b : builtin_scenes()) out.emplace_back(b.name, b.description);
        return out;
      },
      "The built-in scenes as (name, description) pairs.");
}

}  // namespace proxima::python
