// Every study by name: its options as a table of named, typed, documented values, and one
// call that runs it from a map of those values. The sweep manifest (sweep/manifest.h) and the
// Python bindings (`proxima.study.<name>(scene, **options)`) share this mapping instead of
// each copying the options structs field by field.
//
// Option names are the command-line flags without "--", '-' → '_' (`--cube-size` →
// `cube_size`, `--spp` → `spp`); a flag that clears a field (`--no-oracle`) is named after
// the field (`oracle`, default true). Types: "bool", "int", "float", "string"; an enum is a
// "string" with `choices`, a list of enums the same names comma-separated ("nrr,peeling").
// A "float" option also takes "inf" / "-inf" as a string (JSON has no infinity).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/scene.h"
#include "proxima/study/frame_split.h"
#include "proxima/study/gibr.h"
#include "proxima/study/study.h"

namespace proxima::study {

using OptionValue = std::variant<bool, std::int64_t, double, std::string>;
using OptionValues = std::map<std::string, OptionValue>;  // option name → value

struct OptionInfo {
  std::string name;                  // flag without "--", '-' → '_'
  std::string type;                  // "bool" | "int" | "float" | "string"
  std::string doc;                   // one line, from the options struct's comment
  OptionValue default_value;         // the options struct's default
  std::vector<std::string> choices;  // the valid names of an enum; empty = any value of the type
};

struct StudyInfo {
  std::string name;  // the header's name: "envmap_reflect" for study/envmap_reflect.h
  std::string summary;
  std::vector<OptionInfo> options;  // in the order of the options struct
};

// Every study of study/*.h but the demo (which runs studies itself), sorted by name.
const std::vector<StudyInfo>& study_catalog();

// The study named `name`; throws InputError listing the valid names for anything else.
const StudyInfo& study_info(std::string_view name);

// Every option of the study with `options` applied over the defaults, as the study will see
// them (a value given as int for a float option comes back as float, "inf" as a number).
// Throws InputError naming the study or option: unknown study, unknown option, a value of
// the wrong type, an int out of the field's range, an enum name not in `choices`.
OptionValues resolved_options(std::string_view name, const OptionValues& options);

// Runs study `name` on `scene` with `options` over the defaults (run_<name> of its header).
// Throws InputError as resolved_options does, and as the study's validate() does for values
// out of range (those messages name the flag, "--cube-size", of the option `cube_size`).
Results run_study(std::string_view name, const Scene& scene, const OptionValues& options, const StudyOutput& out,
                  Progress* progress = nullptr);

// Whether study `name` splits into frame parts (study/frame_split.h): cluster_reflect and
// visibility. InputError for an unknown study.
bool splits_by_frames(std::string_view name);

// A frame part of study `name` (run_<name>_part of its header), and the whole run's results
// from every part's figures concatenated (<name>_results). InputError for a study that does
// not split, and as run_study.
Results run_study_part(std::string_view name, const Scene& scene, const OptionValues& options, const FramePart& part,
                       const StudyOutput& out, FrameFigures& figures, Progress* progress = nullptr);
Results study_part_results(std::string_view name, const Scene& scene, const OptionValues& options,
                           const FrameFigures& figures);

// The gibr study's options from values (a sweep runs its per-photograph phases as items).
GibrOptions gibr_options(const OptionValues& options);

// A study run as the catalog names it.
struct CatalogRun {
  std::string study;
  std::string scene;  // --scene; the building with --floors N is "building:floors=N"
  OptionValues options;
};

// The study run of a `proxima` command line (without "proxima"): render → reference, sample
// → sampling, shadows, visibility, gibr, bench raster / bench trace, reflect → envmap_reflect
// or, with --method temporal / cluster, temporal_reflect / cluster_reflect. Each flag is the
// option of its name (a bool option: the flag alone sets it, --no-<name> clears it; others
// take the next argument, typed by the catalog); --out and --threads are dropped, and the
// commands' own defaults that differ from the options structs' are applied (sample: --height
// is --width; reflect: --gloss-rays is --glossy-rays). Throws InputError naming the flag for
// one the study does not have or a value that is not of its type.
CatalogRun catalog_run_from_command(const std::vector<std::string>& args);

// The value as text: "true", "42", "0.5", "inf", or the string itself.
std::string option_text(const OptionValue& value);

}  // namespace proxima::study
