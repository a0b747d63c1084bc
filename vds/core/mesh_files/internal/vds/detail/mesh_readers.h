// The mesh file readers behind <vds/mesh_io.h>, one source file per format.
//
// Each parses a whole file held in memory into plain arrays: the file's
// vertices in file order, and each face fanned into triangles (v0, vk, vk+1)
// in file order. Nothing is merged or added (but STL, which has no shared
// vertices: its corners are welded by exact position); faces of fewer than 3
// vertices are dropped and counted in `TriangleMesh::skippedFaces`. Every problem
// is a FormatError naming `name` and the line or byte; sizes declared in
// headers are checked against the bytes there are before anything is
// allocated for them.
#pragma once

#include <cstddef>

#include <vds/mesh.h>

namespace vds::detail {

TriangleMesh readObj(const char* data, std::size_t size, const std::string& name);
TriangleMesh readOff(const char* data, std::size_t size, const std::string& name);
TriangleMesh readPly(const char* data, std::size_t size, const std::string& name);
TriangleMesh readStl(const char* data, std::size_t size, const std::string& name);

/// Appends the triangles of the face `corners` as a fan (a triangle as it
/// is); a face of fewer than 3 vertices adds none and counts in
/// `TriangleMesh::skippedFaces`.
void appendFan(TriangleMesh& mesh, const std::vector<std::uint32_t>& corners);

class Tokens;

/// A vertex line's numbers after its keyword, if any: x y z (finite, within
/// float range), then at most `maxNumbers` - 3 more (colours, normals, ...)
/// that must be numbers, finite or not, and are read past. Throws
/// FormatError at `line` of `name`.
glm::vec3 readVertexLine(Tokens tokens, std::size_t maxNumbers, const std::string& name, std::size_t line);

} // namespace vds::detail
