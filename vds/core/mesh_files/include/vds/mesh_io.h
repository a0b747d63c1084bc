// vds: reading meshes and point sets from files.
//
// The readers are the library's own, small and strict: a file's triangles
// arrive as they are, in plain arrays, and a file that is not what it claims
// to be is refused with the line or byte where it went wrong. docs/formats.md
// says what each format reader takes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds {

/// The mesh file formats `loadMesh` and `parseMesh` read.
enum class MeshFormat : std::uint8_t {
    Obj, ///< Wavefront OBJ: `v` and `f` (v, v/vt, v//vn, v/vt/vn; negative = relative); `\` continues a line; other statements skipped
    Ply, ///< PLY, ascii or binary of either byte order: vertex x, y, z of any type, face vertex_indices lists
    Stl, ///< STL, ASCII or binary (binary is exactly 84 + 50 n bytes); corners welded by exact position
    Off, ///< OFF and its [ST][C][N]OFF variants, counts on the header line or the next, one vertex or face per line
};

/// The format of a file name's extension, in any case: .obj, .ply, .stl, .off.
/// Throws `FormatError` naming `path` for any other.
MeshFormat meshFormatOf(const std::string& path);

/// Reads a triangle mesh from an OBJ, PLY, STL or OFF file (chosen by the
/// extension, `meshFormatOf`). The result holds the file's vertices in file
/// order (STL: each distinct corner position once, in order of first
/// appearance) and its faces in file order, each polygon fanned into
/// triangles (v0, vk, vk+1); nothing is merged or added, and counts a header
/// declares must match what follows. Faces of fewer than 3 vertices (which
/// some exporters write for lines or points) are left out and counted in
/// `skippedFaces`, their indices checked all the same. Numbers after a
/// vertex's x y z (colours, normals, texture coordinates) may be NaN or
/// infinite; x y z may not. `name` is the file name
/// without its directory. Throws `IoError` for a file that cannot be opened
/// or read (missing, a directory), `FormatError` ("<path>:<line>: <what>" or
/// "<path>: byte <n>: <what>") for one that is empty, malformed, truncated,
/// declares more than it holds, or has coordinates that are not finite or do
/// not fit a float, and `OutOfMemory`. Geometry is not judged here: call
/// `validateMesh` on the result.
TriangleMesh loadMesh(const std::string& path);

/// `loadMesh` on a file's content already in memory: `size` bytes at `data`,
/// owned by the caller, not necessarily NUL-terminated. `name` stands for the
/// file in messages and becomes the mesh's `name`. Any bytes at all may be
/// passed: the result is a mesh or an exception, in time and memory linear
/// in `size`.
TriangleMesh parseMesh(const char* data, std::size_t size, MeshFormat format, const std::string& name);

/// The point file formats `loadPoints` and `parsePoints` read.
enum class PointFormat : std::uint8_t {
    Text, ///< lines "x y z"; blank lines and lines starting with '#' ignored
    Ply,  ///< a PLY file's vertices (any faces are read and checked, then ignored)
};

/// Reads points: a .ply file's vertices, or any other file as text lines
/// `x y z`. Throws `IoError`, `FormatError` naming the line (or byte) for
/// anything else, including coordinates that are not finite, and `OutOfMemory`.
std::vector<glm::vec3> loadPoints(const std::string& path);

/// `loadPoints` on content already in memory, as `parseMesh`.
std::vector<glm::vec3> parsePoints(const char* data, std::size_t size, PointFormat format, const std::string& name);

} // namespace vds
