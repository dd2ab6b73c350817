// Text serialization of a winged pair, so many viewpoints reuse one build. Format
// (docs/visibility.md), whitespace-separated, doubles printed with 17 significant digits:
//   proxima-winged-pair 1
//   scale S  polygons P
//   vertices NV    then NV lines: x y z edge
//   edges NE       then NE lines: v0 v1 pair
//   faces NF       then NF lines: cell0 cell1 pair polygon nx ny nz offset
//   cells NC       then NC lines: face
//   pairs NP       then NP lines: face edge clock0 clock1 spin0 spin1 direction
// Absent references are written as -1.
#pragma once

#include <filesystem>

#include "proxima/visibility/winged_pair.h"

namespace proxima::visibility {

// Writes atomically; InputError naming the file when it cannot be written.
void save_winged_pair(const std::filesystem::path& path, const WingedPair& wp);

// Reads and finalizes; InputError naming the file for a missing file, a bad header, a
// truncated or non-numeric field, an out-of-range reference or clock links that do not close.
WingedPair load_winged_pair(const std::filesystem::path& path);

}  // namespace proxima::visibility
