// The action of a command that runs one study on one scene: every input that needs no scene
// is checked, the scene is loaded and the options are checked against it, and only then is
// --out made and the study run into it, so bad input writes nothing.
#pragma once

#include <filesystem>
#include <utility>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/progress.h"
#include "proxima/scene/load.h"
#include "proxima/study/study.h"

namespace proxima::cli {

struct SceneStudyRun {
  std::filesystem::path out;
  Results results;
};

// `run(scene, options, output, progress)` is the study; `images` false writes results only.
// Needs validate(options) and validate(options, scene) beside the options struct.
template <typename Options, typename Run>
SceneStudyRun run_scene_study(const CommonOptions& common, const Options& options, bool images, Run run) {
  if (common.threads < 0) fail_input("--threads: must be ≥ 0");
  validate(options);  // found by argument-dependent lookup in the options' namespace
  ThreadLimit limit(common.threads);
  const Scene scene = load_scene(common.scene);
  validate(options, scene);
  SceneStudyRun done;
  done.out = prepare_out_dir(common.out);
  Progress progress;
  done.results = run(scene, options, study::StudyOutput{images ? done.out : std::filesystem::path()}, &progress);
  return done;
}

}  // namespace proxima::cli
