// Validation of a PLY file before assimp reads it. assimp 5.2's PLY reader
// trusts what the file says: it reserves declared element and list counts before reading
// them (out of memory on a 300-byte file), reads elements it does not know as 0 instances
// (so the lines after them feed the wrong element), and loops or crashes on malformed
// headers (inputs in fuzz/regressions/ply/). So proxima reads the whole file first, to the PLY
// spec, and hands it to assimp only when assimp would read the same thing.
#pragma once

#include <filesystem>

namespace proxima {

// Does nothing for a file that is neither a `.ply` nor starts with the PLY magic (as
// assimp recognizes it). Otherwise throws InputError naming the file unless:
// - the header is printable ASCII keyword lines ending at `end_header` within 64 KiB, with
//   one known format line, well-formed `element NAME COUNT` / `property …` lines, element
//   names unique and not starting with a digit, counts below 2^32, and elements assimp
//   does not read (anything but vertex, face, tristrips, edge, material) only after the
//   ones it reads;
// - the body holds exactly what the header declares: ASCII one instance per line, each
//   value a number of its type (integers in the type's range), list counts matching the
//   values on the line, only blank lines after the last instance; binary list counts
//   non-negative and within the bytes left;
// - every face / tristrip index list is non-empty, at most kMaxFaceVertices long and
//   refers to existing vertices;
// - the vertices and the triangles the faces give fit the limits (core/limits.h).
void check_ply_file(const std::filesystem::path& path);

}  // namespace proxima
