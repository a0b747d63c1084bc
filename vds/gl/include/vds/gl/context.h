// vds: the GL context the library works in, and the one GL rule.
//
// THE GL RULE (every entry point of vds::gl and vds::voxel keeps it):
//  1. A context is passed as `const GlContext&`: first argument of a free
//     function; the constructor's first argument of an object, which keeps
//     it (and must not outlive it). The low-level helpers that act on GL
//     names the caller holds in its current context — `buildProgram`,
//     `setUniforms`, `setStyleUniforms`, `checkGl`, the RAII wrappers of
//     <vds/gl/objects.h> — work on the current context, as GL itself does;
//     objects that upload (`GpuSprite`, the voxel uploads and casters) take
//     a context or, without one, the current context of any origin.
//  2. Any application's context is a valid one: `GlContext::adoptCurrent()`
//     wraps the context current on the calling thread (EGL, GLX, a GLFW or
//     SDL window), without owning it; `GlContext()` makes a headless one of
//     the library's own, a convenience, never a requirement.
//  3. Every call leaves the caller's current context current (saved and
//     restored: EGL display, surfaces and context, or GLX's), also when it
//     throws. Only `GlContext()` and `makeCurrent()` change it, on purpose.
//  4. Programs come from the context's cache (`GlContext::program`): built
//     once per context, never per call or per object.
//  5. GL objects belong to the context and the thread they were made on;
//     using one under another context, or on another thread without first
//     handing its context over (made current there), throws a one-line
//     `GlError` naming the mistake, as does calling with no context
//     current. Nothing GL runs from static destructors (see below).
//
// The headless context: platforms tried (unless VDS_EGL_PLATFORM=surfaceless|device
// forces one): a hardware EGL device (NVIDIA's EGL, or Mesa on a GPU), then
// Mesa's surfaceless platform (llvmpipe on machines without a GPU), then any
// software EGL device. The first that gives desktop GL 4.5 (or at least 4.3)
// core wins. EGL displays are per process and shared with whoever else uses
// them (the application's own EGL context may sit on the same one), so the
// library never calls eglTerminate: a display stays initialized until exit.
//
// Lifetime rules, kept by the types rather than by callers:
//  - an owned context is made current on the thread that creates it;
//  - destroying or moving a context never changes which *other* context is
//    current: the destructor makes its own context current only for as long
//    as it takes to free its programs, then restores the caller's (or, if it
//    was the current one, leaves none current); an adopted context is never
//    destroyed, only its programs and buffers;
//  - GL and EGL are never called once the process has begun to exit: the
//    first context registers an `atexit` handler (which runs before the
//    driver's own teardown) that releases the thread's context and turns
//    every later destruction of a context or GL object into a no-op. A
//    context or program kept in a static therefore cannot crash at exit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <vds/gl/objects.h>

namespace vds {

struct GlInfo {
    std::string platform; ///< "surfaceless", "device" (hardware) or "device (software)"
    std::string vendor;
    std::string renderer; ///< GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version;  ///< GL_VERSION
    int major = 0;
    int minor = 0;
    /// GL runs on the CPU (llvmpipe, softpipe, SwiftShader, a software EGL
    /// device): where the library picks its CPU paths over GL's.
    bool software = false;
    /// "#version 450 core" or "#version 430 core", whichever the context takes.
    std::string glslVersionLine() const;
};

/// What GL allows on a context, as the library's calls need it.
struct GlLimits {
    /// GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the most bytes one shader storage
    /// block, and so one bound buffer range, may hold.
    std::uint64_t maxStorageBlockBytes = 0;
    /// The limits of the context current on the calling thread, asked of GL
    /// (a `GlContext` asks once and keeps them: `GlContext::limits()`).
    static GlLimits query();
};

/// A GL context: the library's own headless EGL context, or the
/// application's, adopted. Move-only.
class GlContext {
public:
    /// Creates and makes current a headless context of the library's own.
    /// Throws `GlUnavailable` with the reasons each platform failed, in one line.
    GlContext();
    /// The context current on the calling thread, whatever made it (EGL, GLX,
    /// a GLFW/SDL/Qt window), wrapped without owning it: the library never
    /// destroys it and, when the handle goes, frees only the programs and
    /// buffers it cached (with the context current, else left to it).
    /// Must not outlive the application's context. Throws `GlError` ("no GL
    /// context current") when none is, and `GlUnavailable` below GL 4.3.
    static GlContext adoptCurrent();
    ~GlContext();
    GlContext(GlContext&&) noexcept;
    GlContext& operator=(GlContext&&) noexcept;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Makes this context current on the calling thread. Throws `GlError` if
    /// it cannot, or if this context was moved from.
    void makeCurrent() const;
    /// True if this context is the one current on the calling thread.
    bool isCurrent() const;
    /// False for a context made by `adoptCurrent()`.
    bool owned() const;
    /// Throws a one-line `GlError` naming `what` unless this context is
    /// current on the calling thread: "no GL context current" or "another GL
    /// context is current".
    void requireCurrent(const char* what) const;
    const GlInfo& info() const;
    /// What GL allows on this context, queried once when it was made or adopted.
    const GlLimits& limits() const;

    /// A program built once per context and kept: `make` runs on first use.
    /// This context must be current (throws `GlError` otherwise): a program
    /// belongs to the context that built it.
    const Program& program(const std::string& key, const std::function<Program()>& make) const;

    /// A GL buffer kept with this context for reuse, by key: the bakers'
    /// scratch space (fragment nodes, counts, prefix sums), which would
    /// otherwise be allocated, and its memory first touched, on every bake.
    /// Holds at least `bytes` bytes (contents undefined, GPU-only storage);
    /// a call asking for more replaces it. Valid until the next call with the
    /// same key, `releaseScratch()`, or the context's end. `capacity`, if
    /// given, receives the size the buffer has (>= bytes). Needs this context current.
    const Buffer& scratchBuffer(const std::string& key, std::size_t bytes, std::size_t* capacity = nullptr) const;
    /// Frees every scratch buffer (this context must be current).
    void releaseScratch() const;

private:
    struct Impl;
    explicit GlContext(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

/// Which context is current on the calling thread, as its API names it
/// (EGL or GLX handles, opaque here): what `CurrentContext` saves and
/// restores, and what `ContextStamp` remembers.
struct NativeContext {
    enum class Api : unsigned char { None, Egl, Glx } api = Api::None;
    void* display = nullptr;
    void* context = nullptr;
    unsigned long glxDraw = 0, glxRead = 0; ///< GLX drawables (XIDs)
    void* eglDraw = nullptr;
    void* eglRead = nullptr;
    /// The context current on the calling thread (`Api::None` where none is).
    static NativeContext current() noexcept;
    /// Makes this context current again (or, for None, releases the current
    /// one); false where the API refuses.
    bool makeCurrent() const noexcept;
    /// The same context, whatever its drawables.
    bool same(const NativeContext& o) const noexcept { return api == o.api && context == o.context; }
};

/// What a GL object remembers of where it was made: the context and the
/// thread (`GpuSprite`, the classifiers and the voxel uploads keep one).
/// `check` throws a one-line `GlError` naming `what` when no
/// context is current, another context is, or the calling thread is
/// another one where the object's context is not current.
class ContextStamp {
public:
    ContextStamp() noexcept = default;
    /// The context current now (throws "no GL context current" if none).
    static ContextStamp current(const char* what);
    void check(const char* what) const;
    /// Only the thread half of `check`.
    void checkThread(const char* what) const;
    /// True when its context is current on the calling thread (false for an empty stamp).
    bool isCurrent() const noexcept;
    explicit operator bool() const noexcept { return native_.api != NativeContext::Api::None; }

private:
    NativeContext native_;
    std::size_t thread_ = 0;
};

/// A scope that restores, when it ends, whichever context was current on the
/// calling thread when it began (or none), of any API. Given a context, it
/// also makes that one current for the scope. Not copyable or movable;
/// thread-bound.
class CurrentContext {
public:
    CurrentContext() noexcept;
    explicit CurrentContext(const GlContext& context);
    ~CurrentContext();
    CurrentContext(const CurrentContext&) = delete;
    CurrentContext& operator=(const CurrentContext&) = delete;

private:
    NativeContext saved_;
};

/// Cheap, non-throwing probe (the answer is computed once per process): can a
/// context be had here? `reason` receives why not.
bool glAvailable(std::string* reason = nullptr);

/// Drains glGetError and throws if it reported anything: `OutOfMemory` when
/// GL_OUT_OF_MEMORY was among the codes, else `GlError`; the message names
/// `what` and every code reported, in order.
void checkGl(const char* what);

} // namespace vds
