// `proxima scenes`: the built-in scenes with their sizes.
#include <cstdio>

#include "command.h"
#include "proxima/scene/builtin_scenes.h"

namespace proxima::cli {

Command register_scenes(CLI::App& root) {
  auto* app = root.add_subcommand("scenes", "list the built-in scenes");
  return {app, [] {
            for (const BuiltinSceneInfo& s : builtin_scenes())
              std::printf("%-16s %s\n", s.name.c_str(), s.description.c_str());
            return 0;
          }};
}

}  // namespace proxima::cli
