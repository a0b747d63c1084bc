// vds: move-only RAII wrappers for GL objects.
//
// Each owns one GL name: `create(...)` makes it (throwing `GlError` if GL
// fails), the destructor deletes it, it is never copied. A default-built
// object owns nothing. `id()` gives the name, `release()` gives it up without
// deleting, `wrap()` adopts a name made elsewhere. The context that made an
// object must be current when the object is destroyed.
#pragma once

#include <utility>

#include <GL/gl.h>

namespace vds {

template <class Traits> class GlObject {
public:
    GlObject() noexcept = default;
    ~GlObject() { reset(); }
    GlObject(GlObject&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    GlObject& operator=(GlObject&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    template <class... Args> static GlObject create(Args... args) { return GlObject(Traits::create(args...)); }
    static GlObject wrap(GLuint id) noexcept { return GlObject(id); }

    GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }
    GLuint release() noexcept { return std::exchange(id_, 0); }
    void reset() noexcept {
        if (id_) Traits::destroy(id_);
        id_ = 0;
    }

private:
    explicit GlObject(GLuint id) noexcept : id_(id) {}
    GLuint id_ = 0;
};

namespace detail {
struct BufferTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
struct TextureTraits { static GLuint create(GLenum target); static void destroy(GLuint) noexcept; };
struct FramebufferTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
struct VertexArrayTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
struct QueryTraits { static GLuint create(GLenum target); static void destroy(GLuint) noexcept; };
struct ShaderTraits { static GLuint create(GLenum type); static void destroy(GLuint) noexcept; };
struct ProgramTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
} // namespace detail

using Buffer = GlObject<detail::BufferTraits>;           ///< create()
using Texture = GlObject<detail::TextureTraits>;         ///< create(GL_TEXTURE_3D, ...)
using Framebuffer = GlObject<detail::FramebufferTraits>; ///< create()
using VertexArray = GlObject<detail::VertexArrayTraits>; ///< create()
using Query = GlObject<detail::QueryTraits>;             ///< create(GL_SAMPLES_PASSED, ...)
using Shader = GlObject<detail::ShaderTraits>;           ///< create(GL_VERTEX_SHADER, ...)
using Program = GlObject<detail::ProgramTraits>;         ///< create(); see <vds/shader.h>

} // namespace vds
