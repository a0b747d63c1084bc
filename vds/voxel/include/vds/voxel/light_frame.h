// vds::voxel: the frame of a directional light (or an orthographic camera)
// in which the shadow and refraction effects build their representations:
// a rotation taking the light's direction of travel to +z, so slicemap
// slices, voxel-grid z and a sprite's Axis::Z all run along the light.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <vds/mesh.h>

namespace vds::voxel {

/// World -> light space of a directional light: a rotation whose third row
/// is the direction the light travels, so light space +z is along the light.
struct LightFrame {
    glm::mat3 toLight{1.0f}; ///< column-major, as GLSL: light = toLight * world

    /// Light-space coordinates of a world point, computed in the same order
    /// as `vdsToLight` in shaders/voxel/transmittance.glsl.
    glm::vec3 toLightSpace(const glm::vec3& world) const;
};

/// The frame of a light travelling along `direction` (any length > 0; throws
/// `InvalidArgument` for zero or non-finite).
LightFrame makeLightFrame(const glm::vec3& direction);

/// A copy of `mesh` with every position in light space (triangles unchanged).
TriangleMesh toLightSpace(MeshView mesh, const LightFrame& frame);

} // namespace vds::voxel
