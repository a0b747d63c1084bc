#include <vds/gl/mesh.h>

#include <algorithm>
#include <limits>

#include <GL/glext.h>
#include <glm/vec3.hpp>

#include <vds/error.h>
#include <vds/gl/context.h>

namespace vds {

GpuMesh::GpuMesh(MeshView mesh) : triangleCount_(mesh.triangleCount) {
    if (mesh.triangleCount * 3 > std::size_t(std::numeric_limits<GLsizei>::max()))
        throw OutOfMemory("mesh has too many triangles for one GL draw");
    positions_ = Buffer::create();
    indices_ = Buffer::create();
    vao_ = VertexArray::create();
    glNamedBufferStorage(positions_.id(), GLsizeiptr(std::max<std::size_t>(1, mesh.positionCount) * sizeof(glm::vec3)),
                         mesh.positionCount ? mesh.positions : nullptr, 0);
    glNamedBufferStorage(indices_.id(), GLsizeiptr(std::max<std::size_t>(1, mesh.triangleCount) * sizeof(glm::uvec3)),
                         mesh.triangleCount ? mesh.triangles : nullptr, 0);
    checkGl("uploading the mesh");
    glVertexArrayVertexBuffer(vao_.id(), 0, positions_.id(), 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(vao_.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_.id(), 0, 0);
    glEnableVertexArrayAttrib(vao_.id(), 0);
    glVertexArrayElementBuffer(vao_.id(), indices_.id());
}

void GpuMesh::draw(GLsizei instances) const {
    glBindVertexArray(vao_.id());
    glDrawElementsInstanced(GL_TRIANGLES, GLsizei(triangleCount_ * 3), GL_UNSIGNED_INT, nullptr, instances);
    glBindVertexArray(0);
}

void GpuMesh::bindStorage(GLuint positionsBinding, GLuint indicesBinding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, positionsBinding, positions_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, indicesBinding, indices_.id());
}

} // namespace vds
