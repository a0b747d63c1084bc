// vds: a headless OpenGL 4.3+ core context through EGL, with no display server.
//
// Platforms tried (unless VDS_EGL_PLATFORM=surfaceless|device forces one):
// a hardware EGL device (NVIDIA's EGL, or Mesa on a GPU), then Mesa's
// surfaceless platform (llvmpipe on machines without a GPU), then any
// software EGL device. The first that gives desktop GL 4.5 (or at least 4.3)
// core wins.
//
// Lifetime rules, kept by the types rather than by callers:
//  - a context is made current on the thread that creates it;
//  - destroying or moving a context never changes which *other* context is
//    current: the destructor makes its own context current only for as long
//    as it takes to free its programs, then restores the caller's (or, if it
//    was the current one, leaves none current);
//  - every library call that is given no context makes a private one inside
//    a `CurrentContext` scope, so the caller's current context (or none) is
//    current again when the call returns;
//  - GL and EGL are never called once the process has begun to exit: the
//    first context registers an `atexit` handler (which runs before the
//    driver's own teardown) that releases the thread's context and turns
//    every later destruction of a context or GL object into a no-op. A
//    context or program kept in a static therefore cannot crash at exit.
#pragma once

#include <cstddef>
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
    /// "#version 450 core" or "#version 430 core", whichever the context takes.
    std::string glslVersionLine() const;
};

/// A move-only EGL display + context, current on the creating thread.
class GlContext {
public:
    /// Creates and makes current a context. Throws `GlUnavailable` with the
    /// reasons each platform failed, in one line.
    GlContext();
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
    const GlInfo& info() const;

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
    std::unique_ptr<Impl> impl_;
};

/// A scope that restores, when it ends, whichever context was current on the
/// calling thread when it began (or none). Given a context, it also makes
/// that one current for the scope. Not copyable or movable; thread-bound.
class CurrentContext {
public:
    CurrentContext() noexcept;
    explicit CurrentContext(const GlContext& context);
    ~CurrentContext();
    CurrentContext(const CurrentContext&) = delete;
    CurrentContext& operator=(const CurrentContext&) = delete;

private:
    void* display_;
    void* draw_;
    void* read_;
    void* context_;
};

/// Cheap, non-throwing probe (the answer is computed once per process): can a
/// context be had here? `reason` receives why not.
bool glAvailable(std::string* reason = nullptr);

/// Drains glGetError and throws if it reported anything: `OutOfMemory` when
/// GL_OUT_OF_MEMORY was among the codes, else `GlError`; the message names
/// `what` and every code reported, in order.
void checkGl(const char* what);

namespace detail {
/// False once the process has begun to exit (see the lifetime rules above):
/// GL objects and contexts then skip their GL and EGL calls.
bool glUsable() noexcept;
} // namespace detail

} // namespace vds
