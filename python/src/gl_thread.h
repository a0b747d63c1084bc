// vds._vds's GL thread: the one thread that runs every GL call of the module
// on its headless context, and the GL objects it keeps (module.cpp's header
// comment tells the whole story).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <utility>

#include <pybind11/pybind11.h>

#include <vds/all.h>

namespace vds::python {


/// The module's GL objects: its context, GPU classifier and sweep, made on
/// first use, the sprites resident on it and the GPU classifiers made on it.
/// Touched only on the GL thread (`GlThread`), where the context stays
/// current: GL objects belong to the thread and context they were made on.
struct GlState {
    std::unique_ptr<vds::GlContext> gl;
    std::unique_ptr<vds::GpuClassifier> classifier;
    std::unique_ptr<vds::GpuOccupancy> occupancy;
    /// GPU copies of Python sprites (`PySprite::gpuId`), kept between
    /// gpu=True calls; released with the context.
    std::unordered_map<std::uint64_t, std::unique_ptr<vds::GpuSprite>> resident;
    /// Classifiers of GPU methods (`PyClassifier::glId`); released with the context.
    std::unordered_map<std::uint64_t, std::unique_ptr<vds::Classifier>> classifiers;

    /// The context, made if need be (and current on the GL thread from then on).
    const vds::GlContext& context() {
        if (!gl) gl = std::make_unique<vds::GlContext>();
        return *gl;
    }

    /// Frees everything, the context last.
    void clear() {
        if (gl) gl->makeCurrent();
        resident.clear();
        classifiers.clear();
        classifier.reset();
        occupancy.reset();
        gl.reset();
    }
};

/// Set in a child made by fork() while the parent's GL thread ran: the
/// driver's own threads (llvmpipe's rasterizer pool, say) did not come along,
/// and GL in the child would wait for them forever.
extern std::atomic<bool> glLostInFork;
extern const char* const kLostInFork;

/// Keys of resident sprites and GPU classifiers, never reused: not across
/// restarts of the GL thread, nor in a forked child (whose sprites may hold
/// their parent's keys).
extern std::atomic<std::uint64_t> nextGlId;

/// One thread that runs every GL call of the module, one task at a time, in
/// the order given: Python threads hand it their GL work and wait (without
/// the GIL), and frees are queued without waiting, so a Python object may be
/// freed on any thread at any time. Started by the first GL task, stopped by
/// `_release_gl` (atexit), which frees the GL objects and the context on
/// this thread; a later GL task starts it again with a new context. Made
/// once and never destroyed (no static destructor may touch GL or threads).
class GlThread {
public:
    /// Runs `task` on the GL thread and waits for it; rethrows its exception.
    /// The caller must not hold the GIL.
    void run(const std::function<void(GlState&)>& task) {
        if (glLostInFork) throw vds::GlUnavailable(kLostInFork);
        std::promise<void> done;
        std::future<void> result = done.get_future();
        {
            std::unique_lock<std::mutex> lock(mutex_);
            start(lock);
            queue_.emplace_back([&task, &done](GlState& state) {
                try {
                    task(state);
                    done.set_value();
                } catch (...) {
                    done.set_exception(std::current_exception());
                }
            });
        }
        wake_.notify_one();
        result.get();
    }

    /// Queues `task` without waiting, if the thread runs (a stopped thread
    /// took every GL object with it: nothing is left to free).
    void post(std::function<void(GlState&)> task) noexcept {
        try {
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                if (!worker_.joinable() || stopping_) return;
                queue_.emplace_back(std::move(task));
            }
            wake_.notify_one();
        } catch (...) {
            // Out of memory queueing a free: the object is freed with the context.
        }
    }

    /// Frees every GL object and the context on the GL thread and stops it.
    void stop() {
        std::thread worker;
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            if (!worker_.joinable()) return;
            stopping_ = true;
            worker.swap(worker_);
        }
        wake_.notify_one();
        worker.join();
        const std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = false;
        live_ = false;
    }

    /// True from the thread's start to the end of `stop`; read without the
    /// mutex (in a child process after fork, another thread may have held it).
    bool live() const noexcept { return live_; }

    bool running() {
        const std::lock_guard<std::mutex> lock(mutex_);
        return worker_.joinable() && !stopping_;
    }

private:
    void start(std::unique_lock<std::mutex>& lock) {
        // A stop under way: let it finish, then start afresh.
        while (stopping_) {
            lock.unlock();
            std::this_thread::yield();
            lock.lock();
        }
        if (!worker_.joinable()) {
            worker_ = std::thread([this] { loop(); });
            live_ = true;
        }
    }

    void loop() {
        GlState state;
        for (;;) {
            std::function<void(GlState&)> task;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
                if (queue_.empty()) break; // stopping, and every task done
                task = std::move(queue_.front());
                queue_.pop_front();
            }
            try {
                task(state); // run()'s tasks hand their exceptions to the caller
            } catch (...) {
                // A free that failed (a context lost): its objects go with the context.
            }
        }
        try {
            state.clear();
        } catch (...) {
            // A context that cannot be made current at exit: its objects go with the process.
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void(GlState&)>> queue_;
    std::thread worker_;
    bool stopping_ = false;
    std::atomic<bool> live_{false};
};

/// The module's GL thread (replaced in a forked child).
GlThread& glThread();
/// pthread_atfork's child handler (see gl_thread.cpp).
void forgetGlThreadInChild();
/// Stops the GL thread, freeing its objects and context (vds._release_gl).
void releaseGl();

} // namespace vds::python
