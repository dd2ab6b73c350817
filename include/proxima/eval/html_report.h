// The HTML report of `proxima demo`: one self-contained page (no scripts, no network; the
// images are files beside it) rendered from a Results — normally read back from the run's
// results.json, so every number on the page is the one in that file.
#pragma once

#include <filesystem>
#include <string>

#include "proxima/eval/results.h"

namespace proxima {

// Page layout: title; machine (CPU, threads), build, commit, command — all from `results`;
// contents; each
// Section with its text, tables (matched by title), images (matched by role, with the
// role as caption), plots (inline SVG charts of table columns, eval/plot.h) and commands; then the tables no section names.
std::string report_html(const Results& results, const std::string& title);

// Writes report_html into out_dir/index.html atomically.
void write_report(const std::filesystem::path& out_dir, const Results& results, const std::string& title);

}  // namespace proxima
