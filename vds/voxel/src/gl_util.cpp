#include "gl_util.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <mutex>

#include <GL/glext.h>

#include <vds/error.h>

namespace vds::voxel::detail {

namespace {
MeshView checkedForStorage(MeshView mesh) {
    requireStorageSize(mesh.positionCount * sizeof(glm::vec3), "the mesh positions");
    requireStorageSize(mesh.triangleCount * sizeof(glm::uvec3), "the mesh indices");
    return mesh;
}
} // namespace

MeshBuffers::MeshBuffers(MeshView mesh) : GpuMesh(checkedForStorage(mesh)) {}

void setGridUniform(GLuint program, const std::string& name, const VoxelGrid& grid) {
    glProgramUniform3fv(program, glGetUniformLocation(program, (name + ".origin").c_str()), 1, &grid.origin[0]);
    glProgramUniform3fv(program, glGetUniformLocation(program, (name + ".scale").c_str()), 1, &grid.scale[0]);
    glProgramUniform3i(program, glGetUniformLocation(program, (name + ".size").c_str()), GLint(grid.size.x),
                       GLint(grid.size.y), GLint(grid.size.z));
}

std::uint32_t rasterViewport(const VoxelGrid& grid) {
    std::uint32_t side = 1;
    while (side < std::max(grid.size.x, grid.size.y)) side *= 2;
    GLint dims[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    if (side > std::uint32_t(std::min(dims[0], dims[1])))
        throw InvalidArgument("a " + std::to_string(grid.size.x) + "x" + std::to_string(grid.size.y) +
                              " column grid needs a " + std::to_string(side) +
                              " pixel viewport, more than GL allows here; lower the resolution");
    return side;
}

RasterState::RasterState(const VoxelGrid& grid, std::uint32_t viewport) {
    glViewport(0, 0, GLsizei(viewport), GLsizei(viewport));
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, GLsizei(grid.size.x), GLsizei(grid.size.y));
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_CLAMP);
    glFrontFace(GL_CW);
}

RasterState::~RasterState() {
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_COLOR_LOGIC_OP);
    glLogicOp(GL_COPY);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ZERO);
    glFrontFace(GL_CCW);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void requireStorageSize(std::size_t bytes, const std::string& what) {
    GLint64 limit = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
    if (bytes > std::size_t(limit))
        throw OutOfMemory(what + " needs " + std::to_string(bytes) + " bytes, more than one GL storage buffer holds (" +
                          std::to_string(limit) + "); lower the resolution");
}

Buffer zeroedBuffer(std::size_t bytes, const char* what) {
    requireStorageSize(bytes, what);
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    if (glGetError() == GL_OUT_OF_MEMORY) throw OutOfMemory(std::string("GL cannot allocate ") + what);
    const GLuint zero = 0;
    glClearNamedBufferData(b.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    checkGl(what);
    return b;
}

void dispatchLinear(std::size_t count, std::uint32_t local) {
    const std::size_t groups = (count + local - 1) / local;
    if (groups == 0) return;
    const std::size_t x = std::min<std::size_t>(groups, 65535);
    const std::size_t y = (groups + x - 1) / x;
    glDispatchCompute(GLuint(x), GLuint(y), 1);
}

std::uint64_t nowNanoseconds() {
    return std::uint64_t(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count());
}

double secondsSince(std::uint64_t start) { return double(nowNanoseconds() - start) * 1e-9; }

DrawTimes timedFullScreenDraw(const char* what) {
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    Query timer = Query::create(GL_TIME_ELAPSED);
    const std::uint64_t start = nowNanoseconds();
    glBeginQuery(GL_TIME_ELAPSED, timer.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    DrawTimes times;
    times.wallMilliseconds = secondsSince(start) * 1e3;
    checkGl(what);
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(timer.id(), GL_QUERY_RESULT, &nanoseconds);
    times.gpuMilliseconds = double(nanoseconds) * 1e-6;
    return times;
}

PlaneTargets::PlaneTargets(std::initializer_list<GLenum> formats, GLsizei width, GLsizei height, const char* what)
    : fbo_(Framebuffer::create()), vao_(VertexArray::create()), width_(width), height_(height) {
    std::vector<GLenum> buffers;
    for (GLenum format : formats) {
        Texture& t = targets_.emplace_back(Texture::create(GL_TEXTURE_2D));
        glTextureStorage2D(t.id(), 1, format, width, height);
        buffers.push_back(GL_COLOR_ATTACHMENT0 + GLenum(buffers.size()));
        glNamedFramebufferTexture(fbo_.id(), buffers.back(), t.id(), 0);
    }
    glNamedFramebufferDrawBuffers(fbo_.id(), GLsizei(buffers.size()), buffers.data());
    if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError(std::string("the ") + what + " framebuffer is incomplete");
}

void PlaneTargets::use(GLuint program) const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width_, height_);
    glUseProgram(program);
}

DrawTimes PlaneTargets::draw(const char* what) const {
    glBindVertexArray(vao_.id());
    const DrawTimes times = timedFullScreenDraw(what);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (GLuint unit = 0; unit < 2; ++unit) glBindTextureUnit(unit, 0);
    return times;
}

} // namespace vds::voxel::detail
