// Validation of a Wavefront OBJ file's face indices before assimp reads it.
// assimp 5.2's OBJ importer checks face / line / point indices only while it builds a
// mesh, and throws "OBJ: vertex index out of range" after allocating that mesh, which it
// then never frees (input: fuzz/regressions/obj/). So proxima checks the
// indices first and refuses the file before assimp allocates anything.
#pragma once

#include <filesystem>

namespace proxima {

// Does nothing unless the file's extension is `.obj` (case-blind). Otherwise reads it line
// by line as assimp does (`v`, `vt`, `vn` lines each add one element; lines starting with
// `f`, `l` or `p` list indices `v`, `v/t`, `v//n`, `v/t/n`, 1-based or negative = relative
// to the elements read so far) and throws InputError naming the file when a vertex index
// is 0 or resolves outside the file's vertices, or a texture-coordinate / normal index
// resolves outside the file's ones while the file has any (assimp ignores them otherwise).
void check_obj_indices(const std::filesystem::path& path);

}  // namespace proxima
