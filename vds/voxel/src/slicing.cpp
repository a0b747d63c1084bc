// Geometry-shader slicing voxelization: Chang, Lai, Yao, Hua, Niu, Liu,
// "Geometry-shader-based real-time voxelization and applications", The
// Visual Computer 30 (2014), section 3 (one pass, the geometry shader slices
// each triangle over its depth range into a 3D texture) and sections 4-5
// (per-voxel fragment counts and normals). Shaders: shaders/voxel/slicing.*.
#include <vds/voxel/slicing.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <GL/glext.h>
#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/gl/shader.h>
#include <vds/mesh_check.h>

#include "raster.h"

namespace vds::voxel {

glm::vec3 SlicedVoxels::normal(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    const glm::vec3 sum(voxels[index(x, y, z)]);
    const float length = glm::length(sum);
    return length > 0.0f ? sum / length : glm::vec3(0.0f);
}

BitGrid SlicedVoxels::occupancy() const {
    BitGrid bits = makeBitGrid(grid);
    for (std::uint32_t z = 0; z < grid.dims.z; ++z)
        for (std::uint32_t y = 0; y < grid.dims.y; ++y)
            for (std::uint32_t x = 0; x < grid.dims.x; ++x)
                if (voxels[index(x, y, z)].w > 0.0f) bits.set(x, y, z, true);
    return bits;
}

SlicedVoxels voxelizeSlices(const GlContext& gl, MeshView mesh, const VoxelGrid& grid, const SlicingOptions& options) {
    requireUsable(validateMesh(mesh), "mesh");
    if (!(options.slabPadding >= 0.0f && options.slabPadding < 1.0f))
        throw InvalidArgument("slab padding must be in [0, 1) cells");
    const CurrentContext current(gl); // the caller's context is current again on return
    GLint max3d = 0, maxLayers = 0, maxVertices = 0, maxComponents = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &maxVertices);
    glGetIntegerv(GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, &maxComponents);
    if (std::max({grid.dims.x, grid.dims.y, grid.dims.z}) > std::uint32_t(max3d) ||
        grid.dims.z > std::uint32_t(maxLayers))
        throw InvalidArgument("a " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) + "x" +
                              std::to_string(grid.dims.z) + " grid exceeds GL's 3D texture size (" +
                              std::to_string(max3d) + "); lower the resolution");
    // Slices one geometry invocation can emit: 3 vertices each, of 4 (position)
    // + 2 (clip distances) + 1 (layer) + 3 (normal) components.
    const int perVertex = 10;
    const std::uint32_t perInstance =
        std::uint32_t(std::clamp(std::min(maxVertices / 3, maxComponents / (3 * perVertex)), 1, 32));
    const Program& program = gl.program("voxel.slicing." + std::to_string(perInstance), [&] {
        return buildProgram({{GL_VERTEX_SHADER, "voxel/slicing.vert", ""},
                             {GL_GEOMETRY_SHADER, "voxel/slicing.geom", ""},
                             {GL_FRAGMENT_SHADER, "voxel/slicing.frag", ""}},
                            "#define VDS_SLICES_PER_INSTANCE " + std::to_string(perInstance) + "\n");
    });

    SlicedVoxels result;
    result.grid = grid;
    result.absorptionPerFragment = options.absorptionPerFragment;
    const std::size_t bytes = grid.cellCount() * sizeof(glm::vec4);
    if (bytes > std::size_t(std::numeric_limits<GLsizei>::max()))
        throw OutOfMemory("voxel properties need " + std::to_string(bytes) +
                          " bytes, more than 2 GiB; lower the resolution");
    try {
        result.voxels.resize(grid.cellCount());
    } catch (const std::bad_alloc&) {
        throw OutOfMemory("cannot allocate " + std::to_string(bytes) + " bytes of voxel properties");
    }
    Texture texture = Texture::create(GL_TEXTURE_3D);
    glTextureStorage3D(texture.id(), 1, GL_RGBA32F, GLsizei(grid.dims.x), GLsizei(grid.dims.y), GLsizei(grid.dims.z));
    if (glGetError() == GL_OUT_OF_MEMORY) throw OutOfMemory("GL cannot allocate the voxel property texture");
    checkGl("allocating the voxel property texture");
    Framebuffer fbo = Framebuffer::create();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, texture.id(), 0); // layered: gl_Layer picks the slice
    glNamedFramebufferDrawBuffer(fbo.id(), GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("slicing voxelization framebuffer is incomplete");
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);

    const std::uint32_t viewport = detail::rasterViewport(grid);
    detail::setGridUniform(program.id(), "u_grid", grid);
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_viewport"), float(viewport));
    glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_padding"), options.slabPadding);
    const detail::MeshBuffers buffers(gl, mesh);
    result.instances = (grid.dims.z + perInstance - 1) / perInstance;
    {
        const detail::RasterState state(grid, viewport);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glUseProgram(program.id());
        glEnable(GL_CLIP_DISTANCE0);
        glEnable(GL_CLIP_DISTANCE1);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        buffers.draw(GLsizei(result.instances));
        glDisable(GL_CLIP_DISTANCE0);
        glDisable(GL_CLIP_DISTANCE1);
    }
    glGetTextureImage(texture.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(bytes), result.voxels.data());
    checkGl("geometry-shader slicing voxelization");
    return result;
}

} // namespace vds::voxel
