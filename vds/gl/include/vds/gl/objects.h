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

/// How `GlObject` makes and deletes each kind of GL name: `create` throws
/// `GlError` when GL gives none; `destroy` does nothing once the process has
/// begun to exit (see <vds/gl/context.h>).
struct BufferTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
struct TextureTraits { static GLuint create(GLenum target); static void destroy(GLuint) noexcept; };
struct FramebufferTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
struct VertexArrayTraits { static GLuint create(); static void destroy(GLuint) noexcept; };
struct QueryTraits { static GLuint create(GLenum target); static void destroy(GLuint) noexcept; };
struct ShaderTraits { static GLuint create(GLenum type); static void destroy(GLuint) noexcept; };
struct ProgramTraits { static GLuint create(); static void destroy(GLuint) noexcept; };

using Buffer = GlObject<BufferTraits>;           ///< create()
using Texture = GlObject<TextureTraits>;         ///< create(GL_TEXTURE_3D, ...)
using Framebuffer = GlObject<FramebufferTraits>; ///< create()
using VertexArray = GlObject<VertexArrayTraits>; ///< create()
using Query = GlObject<QueryTraits>;             ///< create(GL_SAMPLES_PASSED, ...)
using Shader = GlObject<ShaderTraits>;           ///< create(GL_VERTEX_SHADER, ...)
using Program = GlObject<ProgramTraits>;         ///< create(); see <vds/gl/shader.h>

/// A GL fence sync object (a GLsync, not a GLuint name, hence its own type),
/// move-only like the others: `insert()` puts one in the command stream and
/// flushes it to the GPU, the destructor deletes it.
class Fence {
public:
    Fence() noexcept = default;
    ~Fence() { reset(); }
    Fence(Fence&& o) noexcept : sync_(std::exchange(o.sync_, nullptr)) {}
    Fence& operator=(Fence&& o) noexcept {
        if (this != &o) {
            reset();
            sync_ = std::exchange(o.sync_, nullptr);
        }
        return *this;
    }
    Fence(const Fence&) = delete;
    Fence& operator=(const Fence&) = delete;

    /// A fence after every GL command issued so far. Throws `GlError` if GL fails.
    static Fence insert();
    /// Blocks until the GPU has passed the fence. Throws `GlError` if the
    /// wait fails (a lost context). A default-built fence is passed already.
    void wait() const;
    GLsync get() const noexcept { return sync_; }
    explicit operator bool() const noexcept { return sync_ != nullptr; }
    void reset() noexcept;

private:
    GLsync sync_ = nullptr;
};

} // namespace vds
