// The public voxel uploads (<vds/voxel/gpu_grid.h>) sampled by a user's own
// shader through the GLSL lookups: the same answers as the host grids'
// `contains`, for solid voxels and both slicemap slicings.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include <gtest/gtest.h>

#include <vds/gl/shader.h>
#include <vds/voxel/gpu_grid.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/solid.h>
#include "solids.h"

#include "../support/gl_fixture.h"

namespace vds::voxel {
namespace {

using GpuGridTest = test::GlTest;

std::vector<glm::vec3> probes() {
    std::vector<glm::vec3> p;
    const int n = 20;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k)
                p.emplace_back(-1.1f + 2.2f * (float(i) + 0.31f) / float(n), -1.1f + 2.2f * (float(j) + 0.47f) / float(n),
                               -1.1f + 2.2f * (float(k) + 0.59f) / float(n));
    return p;
}

// Runs `lookup` (a GLSL bool expression of `p`) over the points in a user shader.
std::vector<std::uint32_t> runLookup(const Program& program, const std::vector<glm::vec3>& points) {
    Buffer in = Buffer::create(), out = Buffer::create();
    std::vector<glm::vec4> padded;
    for (const auto& p : points) padded.emplace_back(p, 0.0f);
    glNamedBufferStorage(in.id(), GLsizeiptr(padded.size() * 16), padded.data(), 0);
    glNamedBufferStorage(out.id(), GLsizeiptr(points.size() * 4), nullptr, 0);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    glDispatchCompute(GLuint(points.size()), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> labels(points.size());
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(labels.size() * 4), labels.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glUseProgram(0);
    return labels;
}

Program userProgram(const std::string& declarations, const std::string& lookup) {
    return buildProgram({{GL_COMPUTE_SHADER, "mine.comp",
                          "#version 430 core\n" + declarations +
                              "layout(local_size_x = 1) in;\n"
                              "layout(std430, binding = 0) readonly buffer P { vec4 points[]; };\n"
                              "layout(std430, binding = 1) writeonly buffer L { uint labels[]; };\n"
                              "void main() { vec3 p = points[gl_GlobalInvocationID.x].xyz;\n"
                              "  labels[gl_GlobalInvocationID.x] = (" + lookup + ") ? 1u : 0u; }\n"}});
}

TEST_F(GpuGridTest, AUsersShaderSamplesSolidVoxelsAsTheHostGridAnswers) {
    const TriangleMesh mesh = solids::torus({0, 0, 0}, 0.7f, 0.3f, 32).mesh;
    const BitGrid bits = voxelizeSolid(gl(), mesh, makeVoxelGrid(meshBounds(mesh), 40), SolidMethod::Compute);
    const GpuBitGrid uploaded(gl(), bits);
    const Program program = userProgram("#include \"voxel/solid.glsl\"\nuniform usamplerBuffer u_voxels[2];\n"
                                        "uniform VdsVoxelGrid u_voxelGrid[2];\n",
                                        "vdsBitGridContains(u_voxels[1], u_voxelGrid[1], p)");
    uploaded.setUniforms(program.id(), "u_voxels[1]", "u_voxelGrid[1]", 3);
    const auto points = probes();
    const auto labels = runLookup(program, points);
    std::size_t inside = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        EXPECT_EQ(labels[k] != 0, bits.contains(points[k])) << k;
        inside += labels[k];
    }
    EXPECT_GT(inside, 100u);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    glBindTextureUnit(3, 0);
}

TEST_F(GpuGridTest, AUsersShaderSamplesSlicemapsAsTheHostMapAnswers) {
    const TriangleMesh mesh = solids::sphere({0, 0, 0}, 0.9f, 32).mesh;
    for (const Slicing slicing : {Slicing::Uniform, Slicing::Local}) {
        SlicemapOptions options;
        options.slicing = slicing;
        const Slicemap map = buildSlicemap(gl(), mesh, meshBounds(mesh), 48, options);
        const GpuSlicemap uploaded(gl(), map);
        EXPECT_EQ(uploaded.isLocal(), slicing == Slicing::Local);
        const Program program = userProgram(
            "#include \"voxel/slicemap.glsl\"\nuniform usampler2DArray u_slicemap;\nuniform sampler2D u_ranges;\n"
            "uniform VdsSlicemap u_map;\n",
            slicing == Slicing::Local ? "vdsSlicemapLocalContains(u_slicemap, u_ranges, u_map, p)"
                                      : "vdsSlicemapContains(u_slicemap, u_map, p)");
        const GLuint next = uploaded.setUniforms(program.id(), "u_slicemap", "u_ranges", "u_map", 2);
        EXPECT_EQ(next, slicing == Slicing::Local ? 4u : 3u);
        const auto points = probes();
        const auto labels = runLookup(program, points);
        std::size_t inside = 0, differ = 0;
        for (std::size_t k = 0; k < points.size(); ++k) {
            differ += (labels[k] != 0) != map.contains(points[k]);
            inside += labels[k];
        }
        EXPECT_EQ(differ, 0u) << toString(slicing);
        EXPECT_GT(inside, 100u);
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
        for (GLuint unit : {2u, 3u}) glBindTextureUnit(unit, 0);
    }
}

} // namespace
} // namespace vds::voxel
