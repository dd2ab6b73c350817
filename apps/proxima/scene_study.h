// The action of a command that runs one study on one scene, and its publication.
#pragma once

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>

#include "command.h"
#include "proxima/core/parallel.h"
#include "proxima/core/progress.h"
#include "proxima/core/range_check.h"
#include "proxima/scene/load.h"
#include "proxima/study/study.h"

namespace proxima::cli {

// How run_scene_study runs a study.
struct StudyRunOptions {
  bool images = true;  // the study writes its images into --out (false: results.json only)
  // Progress as plain lines when stderr is no terminal (false: only a bar on a terminal).
  bool log_progress = true;
  std::function<Scene()> scene = nullptr;  // the scene; empty = load_scene(--scene)
};

// Whether stderr, where Progress draws, is a terminal.
bool progress_is_terminal();

struct SceneStudyRun {
  std::string scene;  // the scene's name
  std::filesystem::path out;
  Results results;
};

// Makes `out` (prepare_out_dir, InputError naming --out) and calls `study` with it. When
// `study` throws, the directories this call made are removed again if they hold no file.
Results run_in_out_dir(const std::string& out, const std::function<Results(const std::filesystem::path&)>& study);

// Runs `run(scene, options, output, progress)`, the study: the thread count and every option
// that needs no scene are checked (validate(options), found beside the options struct), the
// scene is loaded and the options are checked against it (validate(options, scene), where
// the study has one), then --out is made and the study runs into it. Bad input the study
// finds itself (a camera choice, a file it reads) throws before it writes, and leaves no
// directory behind (run_in_out_dir).
template <typename Options, typename Run>
SceneStudyRun run_scene_study(const CommonOptions& common, const Options& options, Run run,
                              const StudyRunOptions& how = {}) {
  require_at_least(common.threads, 0, "--threads");
  validate(options);
  ThreadLimit limit(common.threads);
  const Scene scene = how.scene ? how.scene() : load_scene(common.scene);
  if constexpr (requires { validate(options, scene); }) validate(options, scene);
  Progress progress;
  Progress* shown = how.log_progress || progress_is_terminal() ? &progress : nullptr;
  SceneStudyRun done;
  done.scene = scene.name;
  done.out = common.out;
  done.results = run_in_out_dir(common.out, [&](const std::filesystem::path& dir) {
    return run(scene, options, study::StudyOutput{how.images ? dir : std::filesystem::path()}, shown);
  });
  return done;
}

// publish_study of the run's results into its --out.
int publish_study(SceneStudyRun run);

}  // namespace proxima::cli
