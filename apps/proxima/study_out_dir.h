// A study run into the --out directory: the directory is made first, so a bad --out fails
// before any work; bad input a study finds while reading (a file it loads, options checked
// against the scene) throws before it writes, and then leaves no directory behind.
#pragma once

#include <functional>
#include <string>

#include "proxima/eval/results.h"
#include "proxima/study/study.h"

namespace proxima::cli {

// Creates `out` (prepare_out_dir, InputError naming --out) and runs `study` into it. When
// `study` throws, the directories this call created are removed again if they hold no file.
Results run_study_into(const std::string& out, const std::function<Results(const study::StudyOutput&)>& study);

}  // namespace proxima::cli
