// `proxima info FILE|NAME`: what a scene holds (triangles, objects, materials, bounds …).
#include <cstdio>

#include "command.h"
#include "proxima/scene/load.h"

namespace proxima::cli {

Command register_info(CLI::App& root) {
  auto* app = root.add_subcommand("info", "print triangles, objects, materials, lights and bounds of a scene");
  static std::string target;
  app->add_option("scene", target, "built-in scene name, .json scene file or mesh file")->required();
  add_limit_flags(app);
  return {app, [] {
            Scene s = load_scene(target);
            Bounds3 b = scene_bounds(s);
            size_t reflective_objects = 0, reflective_triangles = 0;
            std::vector<bool> counted(s.objects.size(), false);
            for (size_t t = 0; t < s.triangles.size(); ++t) {
              if (!s.materials[s.triangle_material[t]].reflective()) continue;
              ++reflective_triangles;
              if (!counted[s.triangle_object[t]]) {
                counted[s.triangle_object[t]] = true;
                ++reflective_objects;
              }
            }
            std::printf("scene:               %s\n", s.name.c_str());
            std::printf("triangles:           %zu\n", s.triangles.size());
            std::printf("vertices:            %zu\n", s.positions.size());
            std::printf("objects:             %zu\n", s.objects.size());
            std::printf("materials:           %zu\n", s.materials.size());
            std::printf("textures:            %zu\n", s.textures.size());
            std::printf("reflective objects:  %zu (%zu triangles)\n", reflective_objects, reflective_triangles);
            std::printf("point lights:        %zu\n", s.point_lights.size());
            std::printf("area lights:         %zu\n", s.area_lights.size());
            std::printf("cameras:             %zu\n", s.cameras.size());
            std::printf("camera paths:        %zu\n", s.camera_paths.size());
            std::printf("animated:            %s\n", has_animation(s) ? "yes" : "no");
            std::printf("dropped degenerate:  %u\n", s.dropped_degenerate);
            std::printf("bounds min:          %g %g %g\n", b.min.x, b.min.y, b.min.z);
            std::printf("bounds max:          %g %g %g\n", b.max.x, b.max.y, b.max.z);
            return 0;
          }};
}

}  // namespace proxima::cli
