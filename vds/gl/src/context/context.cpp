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
#include <unordered_set>
#include <thread>
#include <vector>

#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/detail/context.h>

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

// The EGL displays the library opened alone (not initialized when it
// called eglInitialize, never seen under an adopted context), with the
// count of its own contexts on each. When the last one goes, the display is
// terminated, so that a process that no longer uses GL holds none of the
// driver's threads (a child forked afterwards can start GL of its own); a
// display that was already open, or that the application's context uses, is
// never terminated: other contexts of the process may share it.
std::mutex gDisplayMutex;
std::unordered_map<EGLDisplay, int> gOwnDisplays;
std::unordered_set<EGLDisplay> gSharedDisplays;

void retainOwnDisplay(EGLDisplay d) {
    const std::lock_guard<std::mutex> lock(gDisplayMutex);
    if (!gSharedDisplays.count(d)) ++gOwnDisplays[d];
}

void markShared(EGLDisplay d) {
    const std::lock_guard<std::mutex> lock(gDisplayMutex);
    gSharedDisplays.insert(d);
    gOwnDisplays.erase(d);
}

void releaseOwnDisplay(EGLDisplay d) {
    const std::lock_guard<std::mutex> lock(gDisplayMutex);
    const auto it = gOwnDisplays.find(d);
    if (it == gOwnDisplays.end() || --it->second > 0) return;
    gOwnDisplays.erase(it);
    // Someone else's context current on it: it is shared after all.
    if (eglGetCurrentDisplay() == d && eglGetCurrentContext() != EGL_NO_CONTEXT) {
        gSharedDisplays.insert(d);
        return;
    }
    eglTerminate(d);
}

// Registered after the first eglInitialize, so that it runs before the
// driver's own exit handlers (atexit handlers run in reverse order).
void registerExitHandler() {
    static std::once_flag once;
    std::call_once(once, [] { std::atexit(onExit); });
}

// GLX, looked up only in a process that has loaded it (an application with
// a GLX context, e.g. a GLFW window on X11): vds itself never links GLX.
struct Glx {
    using GetContext = void* (*)();
    using GetDisplay = void* (*)();
    using GetDrawable = unsigned long (*)();
    using MakeContextCurrent = int (*)(void*, unsigned long, unsigned long, void*);
    GetContext getCurrentContext = nullptr;
    GetDisplay getCurrentDisplay = nullptr;
    GetDrawable getCurrentDrawable = nullptr;
    GetDrawable getCurrentReadDrawable = nullptr;
    MakeContextCurrent makeContextCurrent = nullptr;

    // Looked up on every call until found: the application may load GLX
    // after the library's first call.
    static const Glx* get() noexcept {
        static std::atomic<const Glx*> found{nullptr};
        if (const Glx* g = found.load()) return g;
        for (const char* name : {"libGLX.so.0", "libGL.so.1"}) {
            void* lib = dlopen(name, RTLD_LAZY | RTLD_NOLOAD);
            if (!lib) continue;
            auto* g = new Glx; // kept for the process: `found` hands it out
            g->getCurrentContext = reinterpret_cast<GetContext>(dlsym(lib, "glXGetCurrentContext"));
            g->getCurrentDisplay = reinterpret_cast<GetDisplay>(dlsym(lib, "glXGetCurrentDisplay"));
            g->getCurrentDrawable = reinterpret_cast<GetDrawable>(dlsym(lib, "glXGetCurrentDrawable"));
            g->getCurrentReadDrawable = reinterpret_cast<GetDrawable>(dlsym(lib, "glXGetCurrentReadDrawable"));
            g->makeContextCurrent = reinterpret_cast<MakeContextCurrent>(dlsym(lib, "glXMakeContextCurrent"));
            if (!g->getCurrentContext || !g->getCurrentDisplay || !g->getCurrentDrawable ||
                !g->getCurrentReadDrawable || !g->makeContextCurrent) {
                delete g;
                continue;
            }
            const Glx* expected = nullptr;
            if (!found.compare_exchange_strong(expected, g)) delete g;
            return found.load();
        }
        return nullptr;
    }
};

std::size_t threadKey() { return std::hash<std::thread::id>()(std::this_thread::get_id()); }

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
    bool owned = true;
    NativeContext adopted; // the application's context, when not owned
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
    GlInfo info;
    GlLimits limits; // asked once, with the info
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
        if (!owned) {
            // Not ours to destroy: free what we cached in it if it is still
            // current, else leave the names to it (never free them in another).
            if (NativeContext::current().same(adopted)) {
                programs.clear();
                scratch.clear();
            } else {
                for (auto& entry : programs) entry.second.release();
                for (auto& entry : scratch) entry.second.buffer.release();
            }
            return;
        }
        if (display == EGL_NO_DISPLAY) return;
        if (context != EGL_NO_CONTEXT) {
            const bool wasCurrent = eglGetCurrentContext() == context;
            {
                const CurrentContext scope; // the caller's context comes back after the programs go
                native().makeCurrent();
                programs.clear();
                scratch.clear();
            }
            if (wasCurrent) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context); // deferred by EGL while still current elsewhere
        }
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        releaseOwnDisplay(display);
    }

    NativeContext native() const {
        if (!owned) return adopted;
        NativeContext n;
        n.api = NativeContext::Api::Egl;
        n.display = display;
        n.context = context;
        n.eglDraw = n.eglRead = surface;
        return n;
    }

    void readInfo() {
        auto str = [](GLenum e) {
            const GLubyte* s = glGetString(e);
            return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
        };
        info.vendor = str(GL_VENDOR);
        info.renderer = str(GL_RENDERER);
        info.version = str(GL_VERSION);
        glGetIntegerv(GL_MAJOR_VERSION, &info.major);
        glGetIntegerv(GL_MINOR_VERSION, &info.minor);
        info.software = detail::isSoftwareRenderer(info);
        limits = GlLimits::query();
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
        // Already initialized (by the application, or by a context of ours)?
        const bool wasOpen = d != EGL_NO_DISPLAY && eglQueryString(d, EGL_VENDOR) != nullptr;
        if (!wasOpen) (void)eglGetError(); // EGL_NOT_INITIALIZED from the probe
        if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) {
            why = "eglInitialize failed";
            return false;
        }
        registerExitHandler();
        display = d;
        {
            const std::lock_guard<std::mutex> lock(gDisplayMutex);
            if (wasOpen && !gOwnDisplays.count(d)) gSharedDisplays.insert(d); // opened by someone else
        }
        retainOwnDisplay(d); // terminated with our last context only if we opened it alone
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
        // One API's context at a time on a thread: a GLX context (the
        // application's window) is released first; a CurrentContext scope
        // of the caller's brings it back.
        if (NativeContext::current().api == NativeContext::Api::Glx) NativeContext().makeCurrent();
        if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            const EGLint pb[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            if (config != EGL_NO_CONFIG_KHR) surface = eglCreatePbufferSurface(d, config, pb);
            if (surface == EGL_NO_SURFACE || !eglMakeCurrent(d, surface, surface, context)) {
                why = "cannot make the context current";
                return false;
            }
        }
        info.platform = c.name;
        readInfo();
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
            releaseOwnDisplay(display);
        }
        display = EGL_NO_DISPLAY;
        context = EGL_NO_CONTEXT;
        surface = EGL_NO_SURFACE;
    }
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
    const NativeContext before = NativeContext::current(); // current again if this fails
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
    before.makeCurrent();
    throw GlUnavailable(message + ")");
}

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

GlContext GlContext::adoptCurrent() {
    const NativeContext now = NativeContext::current();
    if (now.api == NativeContext::Api::None)
        throw GlError("GlContext::adoptCurrent: no GL context current on this thread");
    auto impl = std::make_unique<Impl>();
    impl->owned = false;
    impl->adopted = now;
    if (now.api == NativeContext::Api::Egl) markShared(static_cast<EGLDisplay>(now.display));
    impl->info.platform = now.api == NativeContext::Api::Egl ? "adopted EGL" : "adopted GLX";
    impl->readInfo();
    if (impl->info.major < 4 || (impl->info.major == 4 && impl->info.minor < 3))
        throw GlUnavailable("GlContext::adoptCurrent: the current context is GL " + impl->info.version +
                            "; vds needs a 4.3+ core context");
    return GlContext(std::move(impl));
}

bool GlContext::owned() const { return impl_ && impl_->owned; }

void GlContext::requireCurrent(const char* what) const {
    if (!impl_) throw GlError(std::string(what) + ": the GL context was moved from");
    const NativeContext now = NativeContext::current();
    if (now.same(impl_->native())) return;
    if (now.api == NativeContext::Api::None) throw GlError(std::string(what) + ": no GL context current");
    throw GlError(std::string(what) + ": another GL context is current, not the one given");
}

GlContext::~GlContext() = default;
GlContext::GlContext(GlContext&&) noexcept = default;
GlContext& GlContext::operator=(GlContext&&) noexcept = default;

void GlContext::makeCurrent() const {
    if (!impl_) throw GlError("cannot make a moved-from GL context current");
    const NativeContext target = impl_->native();
    if (NativeContext::current().same(target)) return;
    if (!target.makeCurrent())
        throw GlError(impl_->owned ? "cannot make the GL context current (is it current on another thread?)"
                                   : "cannot make the adopted GL context current again (destroyed, or current "
                                     "on another thread?)");
}

bool GlContext::isCurrent() const { return impl_ && NativeContext::current().same(impl_->native()); }

NativeContext NativeContext::current() noexcept {
    NativeContext n;
    if (EGLContext c = eglGetCurrentContext(); c != EGL_NO_CONTEXT) {
        n.api = Api::Egl;
        n.context = c;
        n.display = eglGetCurrentDisplay();
        n.eglDraw = eglGetCurrentSurface(EGL_DRAW);
        n.eglRead = eglGetCurrentSurface(EGL_READ);
        return n;
    }
    if (const Glx* glx = Glx::get()) {
        if (void* c = glx->getCurrentContext()) {
            n.api = Api::Glx;
            n.context = c;
            n.display = glx->getCurrentDisplay();
            n.glxDraw = glx->getCurrentDrawable();
            n.glxRead = glx->getCurrentReadDrawable();
        }
    }
    return n;
}

bool NativeContext::makeCurrent() const noexcept {
    const NativeContext now = current();
    if (now.same(*this)) return true;
    // One API's context at a time on a thread (GLVND refuses a switch
    // across APIs): release the current one first.
    if (now.api == Api::Egl && (api != Api::Egl || context == nullptr))
        eglMakeCurrent(now.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (now.api == Api::Glx && api != Api::Glx)
        if (const Glx* glx = Glx::get()) glx->makeContextCurrent(now.display, 0, 0, nullptr);
    switch (api) {
    case Api::None: return true;
    case Api::Egl: return eglMakeCurrent(display, eglDraw, eglRead, context) == EGL_TRUE;
    case Api::Glx: {
        const Glx* glx = Glx::get();
        return glx && glx->makeContextCurrent(display, glxDraw, glxRead, context) != 0;
    }
    }
    return false;
}

ContextStamp ContextStamp::current(const char* what) {
    ContextStamp s;
    s.native_ = NativeContext::current();
    if (s.native_.api == NativeContext::Api::None) throw GlError(std::string(what) + ": no GL context current");
    s.thread_ = threadKey();
    return s;
}

bool ContextStamp::isCurrent() const noexcept {
    return native_.api != NativeContext::Api::None && NativeContext::current().same(native_);
}

// Another thread may use an object only once its context has been handed
// over (made current there): EGL and GLX allow a context on one thread at a time.
void ContextStamp::checkThread(const char* what) const {
    if (native_.api == NativeContext::Api::None)
        throw GlError(std::string(what) + ": the object is empty (default-made or moved from)");
    if (thread_ != threadKey() && !NativeContext::current().same(native_))
        throw GlError(std::string(what) +
                      ": called on another thread than the one the object was made on, without its GL context current");
}

void ContextStamp::check(const char* what) const {
    checkThread(what);
    const NativeContext now = NativeContext::current();
    if (now.same(native_)) return;
    if (now.api == NativeContext::Api::None) throw GlError(std::string(what) + ": no GL context current");
    throw GlError(std::string(what) + ": made in another GL context than the one current");
}

CurrentContext::CurrentContext() noexcept : saved_(NativeContext::current()) {}

CurrentContext::CurrentContext(const GlContext& context) : CurrentContext() { context.makeCurrent(); }

CurrentContext::~CurrentContext() {
    if (gExiting) return;
    saved_.makeCurrent();
}

const GlInfo& GlContext::info() const { return impl_->info; }

const Program& GlContext::program(const std::string& key, const std::function<Program()>& make) const {
    requireCurrent(("program '" + key + "'").c_str());
    auto it = impl_->programs.find(key);
    if (it == impl_->programs.end()) it = impl_->programs.emplace(key, make()).first;
    return it->second;
}

const Buffer& GlContext::scratchBuffer(const std::string& key, std::size_t bytes, std::size_t* capacity) const {
    requireCurrent(("scratch buffer '" + key + "'").c_str());
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
            const CurrentContext keep; // the caller's context (or none) is current again after the probe
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

bool isSoftwareRenderer(const GlInfo& info) {
    const std::string& renderer = info.renderer;
    return info.platform.find("software") != std::string::npos || renderer.find("llvmpipe") != std::string::npos ||
           renderer.find("softpipe") != std::string::npos || renderer.find("SwiftShader") != std::string::npos;
}
} // namespace detail

GlLimits GlLimits::query() {
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    GlLimits limits;
    limits.maxStorageBlockBytes = std::uint64_t(std::max<GLint64>(maxBlock, 0));
    return limits;
}

const GlLimits& GlContext::limits() const { return impl_->limits; }

} // namespace vds
