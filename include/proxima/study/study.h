// What every study shares. A study is one experiment as a library call: a technique beside
// its reference over a camera, a path or a set of views, measured and tabulated. Each study
// header (study/<name>.h) has an options struct with documented defaults, a validate()
// whose messages name the command-line flag, and
//   Results run_<name>(const Scene&, const <Name>Options&, const StudyOutput&, Progress*)
// returning the metrics, tables and image roles the command line publishes. The command
// line, the demo, the tests and the bindings all call the studies in-process.
#pragma once

#include <filesystem>
#include <string>

#include "proxima/core/image.h"
#include "proxima/core/progress.h"
#include "proxima/eval/results.h"

namespace proxima::study {

// Where a study writes its images (PNG files named in Results::images, relative to `dir`).
// An empty `dir` writes nothing: the results alone (tests, bindings).
struct StudyOutput {
  std::filesystem::path dir;

  bool writes() const { return !dir.empty(); }
};

// Writes `image` as out.dir/file (PNG, linear → sRGB) and records it in results.images under
// `role`; does nothing when `out` has no directory.
void write_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                 const ImageF& image);
// The same as EXR (float channels as they are), for depth, normals and ids.
void write_exr_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                     const ImageF& image);

// Triangle ids as one float channel for EXR: exact up to 2^24, −1 where no triangle was hit.
ImageF triangle_ids_as_float(const ImageU32& ids);

}  // namespace proxima::study
