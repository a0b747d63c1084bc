// vds: a headless OpenGL 4.3+ core context through EGL, with no display server.
//
// Platforms tried (unless VDS_EGL_PLATFORM=surfaceless|device forces one):
// a hardware EGL device (NVIDIA's EGL, or Mesa on a GPU), then Mesa's
// surfaceless platform (llvmpipe on machines without a GPU), then any
// software EGL device. The first that gives desktop GL 4.5 (or at least 4.3)
// core wins. Every GL call of the library needs a context current on the
// calling thread; a context is made current on the thread that creates it.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <vds/gl_objects.h>

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

    /// Makes this context current on the calling thread.
    void makeCurrent() const;
    const GlInfo& info() const;

    /// A program built once per context and kept: `make` runs on first use.
    const Program& program(const std::string& key, const std::function<Program()>& make) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Cheap, non-throwing probe (the answer is computed once per process): can a
/// context be had here? `reason` receives why not.
bool glAvailable(std::string* reason = nullptr);

/// Throws `GlError` naming `what` and the GL error code if glGetError reports one.
void checkGl(const char* what);

} // namespace vds
