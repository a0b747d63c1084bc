#include <vds/gl_objects.h>

#include <GL/glext.h>

#include <vds/error.h>

namespace vds::detail {
namespace {
GLuint checked(GLuint id, const char* what) {
    if (id == 0) throw GlError(std::string("cannot create GL ") + what);
    return id;
}
} // namespace

GLuint BufferTraits::create() { GLuint id = 0; glCreateBuffers(1, &id); return checked(id, "buffer"); }
void BufferTraits::destroy(GLuint id) noexcept { glDeleteBuffers(1, &id); }
GLuint TextureTraits::create(GLenum target) { GLuint id = 0; glCreateTextures(target, 1, &id); return checked(id, "texture"); }
void TextureTraits::destroy(GLuint id) noexcept { glDeleteTextures(1, &id); }
GLuint FramebufferTraits::create() { GLuint id = 0; glCreateFramebuffers(1, &id); return checked(id, "framebuffer"); }
void FramebufferTraits::destroy(GLuint id) noexcept { glDeleteFramebuffers(1, &id); }
GLuint VertexArrayTraits::create() { GLuint id = 0; glCreateVertexArrays(1, &id); return checked(id, "vertex array"); }
void VertexArrayTraits::destroy(GLuint id) noexcept { glDeleteVertexArrays(1, &id); }
GLuint QueryTraits::create(GLenum target) { GLuint id = 0; glCreateQueries(target, 1, &id); return checked(id, "query"); }
void QueryTraits::destroy(GLuint id) noexcept { glDeleteQueries(1, &id); }
GLuint ShaderTraits::create(GLenum type) { return checked(glCreateShader(type), "shader"); }
void ShaderTraits::destroy(GLuint id) noexcept { glDeleteShader(id); }
GLuint ProgramTraits::create() { return checked(glCreateProgram(), "program"); }
void ProgramTraits::destroy(GLuint id) noexcept { glDeleteProgram(id); }

} // namespace vds::detail
