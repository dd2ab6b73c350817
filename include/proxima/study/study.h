// What every study shares. A study is one experiment as a library call: a technique beside
// its reference over a camera, a path or a set of views, measured and tabulated. Each study
// header (study/<name>.h) has an options struct with documented defaults, a validate()
// whose messages name the command-line flag, and
//   Results run_<name>(const Scene&, const <Name>Options&, const StudyOutput&, Progress*)
// returning the metrics, tables and image roles the command line publishes. The command
// line, the demo, the tests and the bindings all call the studies in-process.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "proxima/core/image.h"
#include "proxima/core/progress.h"
#include "proxima/eval/results.h"

namespace proxima::study {

// Where a study writes its images (PNG files named in Results::images, relative to `dir`).
// An empty `dir` writes nothing: the results alone (tests, bindings).
struct StudyOutput {
  std::filesystem::path dir;
  // Non-null: every image published under a role is also kept here (role → the image
  // before encoding: linear RGB for a PNG, the channels of an EXR), with or without `dir`.
  std::map<std::string, ImageF>* kept = nullptr;

  bool writes() const { return !dir.empty(); }
  bool keeps() const { return kept != nullptr; }
  // Whether the study's images are wanted at all (written or kept).
  bool wants_images() const { return writes() || keeps(); }
};

// Writes `image` as out.dir/file (PNG, linear → sRGB) and records it in results.images under
// `role`; keeps a copy under `role` when `out` keeps images. Without a directory nothing is
// written or recorded.
void write_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                 const ImageF& image);
// The same as EXR (float channels as they are), for depth, normals and ids.
void write_exr_image(const StudyOutput& out, Results& results, const std::string& role, const std::string& file,
                     const ImageF& image);
// Keeps a copy of `image` under `role` when `out` keeps images (for images a study writes
// itself, outside write_image); does nothing otherwise.
void keep_image(const StudyOutput& out, const std::string& role, const ImageF& image);

// Triangle ids as one float channel for EXR: exact up to 2^24, −1 where no triangle was hit.
ImageF triangle_ids_as_float(const ImageU32& ids);

}  // namespace proxima::study
