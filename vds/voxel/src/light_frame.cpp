// The frame of a directional light: a rotation taking its direction to +z.
#include <vds/voxel/light_frame.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <vds/error.h>

namespace vds::voxel {

glm::vec3 LightFrame::toLightSpace(const glm::vec3& w) const {
    const glm::mat3& m = toLight;
    return {(m[0][0] * w.x + m[1][0] * w.y) + m[2][0] * w.z, (m[0][1] * w.x + m[1][1] * w.y) + m[2][1] * w.z,
            (m[0][2] * w.x + m[1][2] * w.y) + m[2][2] * w.z};
}

LightFrame makeLightFrame(const glm::vec3& direction) {
    const float length = glm::length(direction);
    if (!(std::isfinite(length) && length > 0.0f))
        throw InvalidArgument("the light direction must be a finite, non-zero vector");
    const glm::vec3 z = direction / length;
    // Any vector not along z gives the other two axes.
    const glm::vec3 helper = std::fabs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 x = glm::normalize(glm::cross(helper, z));
    const glm::vec3 y = glm::cross(z, x);
    LightFrame frame;
    frame.toLight = glm::transpose(glm::mat3(x, y, z)); // rows x, y, z
    return frame;
}

TriangleMesh toLightSpace(MeshView mesh, const LightFrame& frame) {
    TriangleMesh out;
    out.positions.reserve(mesh.positionCount);
    for (std::size_t i = 0; i < mesh.positionCount; ++i) out.positions.push_back(frame.toLightSpace(mesh.positions[i]));
    out.triangles.assign(mesh.triangles, mesh.triangles + mesh.triangleCount);
    return out;
}

} // namespace vds::voxel
