// vds: a triangle mesh on the GPU, drawn by the bakers, the voxelizers and
// the samples.
#pragma once

#include <cstddef>

#include <GL/gl.h>

#include <vds/gl/objects.h>
#include <vds/mesh.h>

namespace vds {

/// Positions (x y z floats, attribute 0) and indices (three uint32 per
/// triangle) in GL buffers, with a vertex array that draws them. The buffers
/// double as shader storage (`bindStorage`), for compute passes over the
/// triangles. Move-only, like every GL object; needs a current context.
class GpuMesh {
public:
    GpuMesh() = default;
    /// Uploads the mesh. Throws `OutOfMemory` past one draw call's index
    /// count, `GlError` if GL refuses the buffers.
    explicit GpuMesh(MeshView mesh);

    const Buffer& positions() const { return positions_; }
    const Buffer& indices() const { return indices_; }
    const VertexArray& vertexArray() const { return vao_; }
    std::size_t triangleCount() const { return triangleCount_; }

    /// glDrawElements(GL_TRIANGLES) over every triangle; `instances` > 1 draws instanced.
    void draw(GLsizei instances = 1) const;
    /// Binds positions and indices as shader storage buffers.
    void bindStorage(GLuint positionsBinding = 0, GLuint indicesBinding = 1) const;

private:
    Buffer positions_;
    Buffer indices_;
    VertexArray vao_;
    std::size_t triangleCount_ = 0;
};

} // namespace vds
