// vds: reading meshes and point sets from files, through OpenMesh.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds {

/// Reads a triangle mesh from OBJ, PLY, STL or OFF (chosen by extension).
/// Polygons are fan-triangulated. Throws `IoError` for a missing or unreadable
/// file and `FormatError` for one OpenMesh cannot parse. Geometry is not
/// judged here: call `validateMesh` on the result.
TriangleMesh loadMesh(const std::string& path);

/// Reads points: a PLY file (its vertices) or a text file of lines `x y z`
/// (blank lines and lines starting with '#' ignored). Throws `FormatError`
/// naming the line for anything else, including non-finite values.
std::vector<glm::vec3> loadPoints(const std::string& path);

} // namespace vds
