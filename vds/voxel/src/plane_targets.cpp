#include "plane_targets.h"

#include <chrono>
#include <string>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/context.h>

namespace vds::voxel::detail {

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
