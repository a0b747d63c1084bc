#include <vds/gl/context.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <unordered_map>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <vds/error.h>

namespace vds {
namespace {

// Set by the atexit handler: from then on no GL or EGL call is made.
std::atomic<bool> gExiting{false};

void onExit() {
    gExiting = true;
    // Whatever context this thread holds is released while the driver is
    // still alive; the contexts themselves go with the process.
    if (eglGetCurrentContext() != EGL_NO_CONTEXT)
        eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglReleaseThread();
}

// Registered after the first eglInitialize, so that it runs before the
// driver's own exit handlers (atexit handlers run in reverse order).
void registerExitHandler() {
    static std::once_flag once;
    std::call_once(once, [] { std::atexit(onExit); });
}

// EGL displays are per process: terminate one only when its last context goes.
std::mutex gDisplayMutex;
std::map<EGLDisplay, int> gDisplayUsers;

void retainDisplay(EGLDisplay d) {
    std::lock_guard<std::mutex> lock(gDisplayMutex);
    ++gDisplayUsers[d];
}
void releaseDisplay(EGLDisplay d) {
    std::lock_guard<std::mutex> lock(gDisplayMutex);
    if (--gDisplayUsers[d] == 0) {
        gDisplayUsers.erase(d);
        eglTerminate(d);
    }
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

struct Candidate {
    std::string name;
    EGLenum platform;
    void* nativeDisplay;
};

std::vector<Candidate> candidates(std::string& notes) {
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const char* force = std::getenv("VDS_EGL_PLATFORM");
    const std::string forced = force ? force : "";
    std::vector<Candidate> hardware, software;
    const bool surfaceless = hasExtension(clientExt, "EGL_MESA_platform_surfaceless");
    if (hasExtension(clientExt, "EGL_EXT_device_enumeration") || hasExtension(clientExt, "EGL_EXT_device_base")) {
        auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto queryDeviceString =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        EGLint count = 0;
        if (queryDevices && queryDevices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(std::size_t(count), nullptr);
            queryDevices(count, devices.data(), &count);
            for (EGLint i = 0; i < count; ++i) {
                const char* ext = queryDeviceString ? queryDeviceString(devices[std::size_t(i)], EGL_EXTENSIONS) : nullptr;
                const bool isSoftware = hasExtension(ext, "EGL_MESA_device_software");
                (isSoftware ? software : hardware)
                    .push_back({isSoftware ? "device (software)" : "device", EGL_PLATFORM_DEVICE_EXT,
                                devices[std::size_t(i)]});
            }
        }
    } else {
        notes += "no EGL device enumeration; ";
    }
    std::vector<Candidate> order;
    if (forced.empty() || forced == "device")
        order.insert(order.end(), hardware.begin(), hardware.end());
    if ((forced.empty() || forced == "surfaceless") && surfaceless)
        order.push_back({"surfaceless", EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY});
    if (forced.empty() || forced == "device")
        order.insert(order.end(), software.begin(), software.end());
    if (!forced.empty() && forced != "device" && forced != "surfaceless")
        notes += "VDS_EGL_PLATFORM='" + forced + "' is neither 'surfaceless' nor 'device'; ";
    if (!surfaceless) notes += "no EGL_MESA_platform_surfaceless; ";
    return order;
}

} // namespace

std::string GlInfo::glslVersionLine() const {
    return (major > 4 || (major == 4 && minor >= 5)) ? "#version 450 core" : "#version 430 core";
}

struct GlContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
    GlInfo info;
    mutable std::unordered_map<std::string, Program> programs;
    struct Scratch {
        std::size_t bytes = 0;
        Buffer buffer;
    };
    mutable std::unordered_map<std::string, Scratch> scratch;

    ~Impl() {
        if (gExiting) {
            // The driver may be gone: let the programs' and buffers' names go unfreed.
            for (auto& entry : programs) entry.second.release();
            for (auto& entry : scratch) entry.second.buffer.release();
            return;
        }
        if (display == EGL_NO_DISPLAY) return;
        if (context != EGL_NO_CONTEXT) {
            const bool wasCurrent = eglGetCurrentContext() == context;
            {
                const CurrentContext scope; // the caller's context comes back after the programs go
                eglMakeCurrent(display, surface, surface, context);
                programs.clear();
                scratch.clear();
            }
            if (wasCurrent) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context); // deferred by EGL while still current elsewhere
        }
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        releaseDisplay(display);
    }

    // Tries one platform; on failure leaves `why` and cleans up.
    bool tryCandidate(const Candidate& c, std::string& why) {
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!getPlatformDisplay) {
            why = "no eglGetPlatformDisplayEXT";
            return false;
        }
        EGLDisplay d = getPlatformDisplay(c.platform, c.nativeDisplay, nullptr);
        EGLint major = 0, minor = 0;
        if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) {
            why = "eglInitialize failed";
            return false;
        }
        registerExitHandler();
        retainDisplay(d);
        display = d;
        if (!eglBindAPI(EGL_OPENGL_API)) {
            why = "no desktop OpenGL API";
            return false;
        }
        const char* ext = eglQueryString(d, EGL_EXTENSIONS);
        EGLConfig config = nullptr;
        EGLint n = 0;
        const EGLint pbufferAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
        const EGLint anyAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        if (!eglChooseConfig(d, pbufferAttribs, &config, 1, &n) || n == 0) {
            n = 0;
            if (!eglChooseConfig(d, anyAttribs, &config, 1, &n) || n == 0) {
                if (!hasExtension(ext, "EGL_KHR_no_config_context")) {
                    why = "no OpenGL config";
                    return false;
                }
                config = EGL_NO_CONFIG_KHR;
            }
        }
        for (int wantMinor : {5, 3}) {
            const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, wantMinor,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
            context = eglCreateContext(d, config, EGL_NO_CONTEXT, attribs);
            if (context != EGL_NO_CONTEXT) break;
        }
        if (context == EGL_NO_CONTEXT) {
            why = "no OpenGL 4.3 core context";
            return false;
        }
        if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            if (config != EGL_NO_CONFIG_KHR) surface = eglCreatePbufferSurface(d, config, pb);
            if (surface == EGL_NO_SURFACE || !eglMakeCurrent(d, surface, surface, context)) {
                why = "cannot make the context current";
                return false;
            }
        }
        auto str = [](GLenum e) {
            const GLubyte* s = glGetString(e);
            return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
        };
        info.platform = c.name;
        info.vendor = str(GL_VENDOR);
        info.renderer = str(GL_RENDERER);
        info.version = str(GL_VERSION);
        glGetIntegerv(GL_MAJOR_VERSION, &info.major);
        glGetIntegerv(GL_MINOR_VERSION, &info.minor);
        if (info.major < 4 || (info.major == 4 && info.minor < 3)) {
            why = "GL " + info.version + " is below 4.3";
            return false;
        }
        return true;
    }

    // Undoes a failed tryCandidate (the context, if any, is current here).
    void reset() {
        if (display != EGL_NO_DISPLAY) {
            if (context != EGL_NO_CONTEXT && eglGetCurrentContext() == context)
                eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
            if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
            releaseDisplay(display);
        }
        display = EGL_NO_DISPLAY;
        context = EGL_NO_CONTEXT;
        surface = EGL_NO_SURFACE;
    }
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
    std::string notes;
    const auto order = candidates(notes);
    std::string reasons;
    for (const auto& c : order) {
        std::string why;
        if (impl_->tryCandidate(c, why)) return;
        reasons += c.name + ": " + why + "; ";
        impl_->reset();
    }
    std::string message = "no OpenGL 4.3+ context could be created (" + reasons + notes;
    if (order.empty()) message += "no EGL platform available; ";
    message.resize(message.size() - 2);
    throw GlUnavailable(message + ")");
}

GlContext::~GlContext() = default;
GlContext::GlContext(GlContext&&) noexcept = default;
GlContext& GlContext::operator=(GlContext&&) noexcept = default;

void GlContext::makeCurrent() const {
    if (!impl_) throw GlError("cannot make a moved-from GL context current");
    if (eglGetCurrentContext() == impl_->context) return;
    if (!eglMakeCurrent(impl_->display, impl_->surface, impl_->surface, impl_->context))
        throw GlError("cannot make the GL context current");
}

bool GlContext::isCurrent() const { return impl_ && eglGetCurrentContext() == impl_->context; }

CurrentContext::CurrentContext() noexcept
    : display_(eglGetCurrentDisplay()), draw_(eglGetCurrentSurface(EGL_DRAW)), read_(eglGetCurrentSurface(EGL_READ)),
      context_(eglGetCurrentContext()) {}

CurrentContext::CurrentContext(const GlContext& context) : CurrentContext() { context.makeCurrent(); }

CurrentContext::~CurrentContext() {
    if (gExiting || eglGetCurrentContext() == context_) return;
    if (context_ != EGL_NO_CONTEXT) {
        eglMakeCurrent(display_, draw_, read_, context_);
    } else if (EGLDisplay now = eglGetCurrentDisplay(); now != EGL_NO_DISPLAY) {
        eglMakeCurrent(now, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
}

const GlInfo& GlContext::info() const { return impl_->info; }

const Program& GlContext::program(const std::string& key, const std::function<Program()>& make) const {
    if (!isCurrent()) throw GlError("program '" + key + "' asked of a GL context that is not current");
    auto it = impl_->programs.find(key);
    if (it == impl_->programs.end()) it = impl_->programs.emplace(key, make()).first;
    return it->second;
}

const Buffer& GlContext::scratchBuffer(const std::string& key, std::size_t bytes, std::size_t* capacity) const {
    Impl::Scratch& entry = impl_->scratch[key];
    if (capacity) *capacity = std::max(entry.bytes, bytes);
    if (entry.buffer && entry.bytes >= bytes) return entry.buffer;
    entry.buffer = Buffer(); // free the old storage before asking for the new
    entry.bytes = 0;
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), nullptr, 0);
    checkGl(("allocating scratch buffer " + key).c_str());
    entry.buffer = std::move(b);
    entry.bytes = bytes;
    return entry.buffer;
}

void GlContext::releaseScratch() const { impl_->scratch.clear(); }

bool glAvailable(std::string* reason) {
    static std::once_flag once;
    static bool available = false;
    static std::string why;
    std::call_once(once, [] {
        try {
            GlContext probe;
            available = true;
        } catch (const std::exception& e) {
            why = e.what();
        }
    });
    if (reason) *reason = why;
    return available;
}

namespace {
std::string errorName(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04x", e);
        return std::string("GL error ") + hex;
    }
    }
}
} // namespace

void checkGl(const char* what) {
    std::string names;
    bool outOfMemory = false;
    // A lost context reports GL_CONTEXT_LOST forever: stop after a few codes.
    for (int k = 0; k < 8; ++k) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        outOfMemory |= e == GL_OUT_OF_MEMORY;
        names += (names.empty() ? "" : ", ") + errorName(e);
    }
    if (names.empty()) return;
    if (outOfMemory) throw OutOfMemory(std::string(what) + ": GL is out of memory (" + names + ")");
    throw GlError(std::string(what) + ": " + names);
}

namespace detail {
bool glUsable() noexcept { return !gExiting; }
} // namespace detail

} // namespace vds
