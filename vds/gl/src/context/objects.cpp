#include <vds/gl/objects.h>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/context.h>
#include <vds/gl/detail/context.h>

namespace vds {
namespace {
GLuint checked(GLuint id, const char* what) {
    if (id == 0) throw GlError(std::string("cannot create GL ") + what);
    return id;
}
} // namespace

GLuint BufferTraits::create() { GLuint id = 0; glCreateBuffers(1, &id); return checked(id, "buffer"); }
void BufferTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteBuffers(1, &id); }
GLuint TextureTraits::create(GLenum target) { GLuint id = 0; glCreateTextures(target, 1, &id); return checked(id, "texture"); }
void TextureTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteTextures(1, &id); }
GLuint FramebufferTraits::create() { GLuint id = 0; glCreateFramebuffers(1, &id); return checked(id, "framebuffer"); }
void FramebufferTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteFramebuffers(1, &id); }
GLuint VertexArrayTraits::create() { GLuint id = 0; glCreateVertexArrays(1, &id); return checked(id, "vertex array"); }
void VertexArrayTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteVertexArrays(1, &id); }
GLuint QueryTraits::create(GLenum target) { GLuint id = 0; glCreateQueries(target, 1, &id); return checked(id, "query"); }
void QueryTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteQueries(1, &id); }
GLuint ShaderTraits::create(GLenum type) { return checked(glCreateShader(type), "shader"); }
void ShaderTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteShader(id); }
GLuint ProgramTraits::create() { return checked(glCreateProgram(), "program"); }
void ProgramTraits::destroy(GLuint id) noexcept { if (detail::glUsable()) glDeleteProgram(id); }

} // namespace vds

namespace vds {

Fence Fence::insert() {
    Fence f;
    f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!f.sync_) throw GlError("cannot create a GL fence");
    glFlush(); // a fence that never reaches the GPU is never passed
    return f;
}

void Fence::wait() const {
    if (!sync_) return;
    for (;;) {
        const GLenum r = glClientWaitSync(sync_, 0, GLuint64(1000000000));
        if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) return;
        if (r == GL_WAIT_FAILED) throw GlError("waiting for a GL fence failed");
    }
}

void Fence::reset() noexcept {
    if (sync_ && detail::glUsable()) glDeleteSync(sync_);
    sync_ = nullptr;
}

} // namespace vds
