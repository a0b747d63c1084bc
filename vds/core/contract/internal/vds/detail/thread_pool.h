// vds: the library's threads: one pool, started as calls need it and kept
// for the process, on which every batch split over threads runs
// (<vds/detail/parallel.h>) and the GL layer's host copies too.
#pragma once

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace vds::detail {

/// Threads kept between calls: starting one costs tens of microseconds, as
/// much as a small batch's work, so a thread is started once per process.
///
/// A call runs its task on the calling thread and on up to `helpers` pool
/// threads at once. The caller always runs the task itself and then waits
/// only for the helpers that took it; one that had not taken it by then
/// never will. So a call never waits on a thread that is busy elsewhere,
/// and a task may itself call `run` (a nested `parallelFor`) on any number
/// of levels without deadlock. When fewer threads are idle than the calls
/// in progress ask for, the pool starts more (kept too): a call gets the
/// threads it asks for, as when each call started its own.
///
/// Thread safe: any thread may call `run`, several at once. A child made by
/// fork() (which copies only the forking thread) gets a pool that has
/// forgotten the parent's threads and starts its own.
class ThreadPool {
public:
    /// The process's pool, or null once static destruction has destroyed it
    /// (then callers run their work on the calling thread alone). Its
    /// threads are joined at that destruction, so none outlives `main`'s
    /// statics.
    static ThreadPool* shared();
    /// std::thread::hardware_concurrency(), at least 1, read once.
    static unsigned hardwareThreads();

    ThreadPool() = default;
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// Runs task(context) on the calling thread and on up to `helpers` pool
    /// threads at once; returns when every one of those runs has returned.
    /// `task` must not throw (`parallelFor` catches its body's exceptions).
    /// Fewer helpers run it where the system refuses new threads.
    void run(unsigned helpers, void (*task)(void*), void* context);

    /// Threads the pool holds (for tests).
    unsigned size();

private:
    struct Job;
    static void beforeFork();
    static void afterForkInParent();
    static void afterForkInChild();
    void serve();
    Job* openJob() const;
    void startThreads(unsigned count);

    std::mutex mutex_;
    std::condition_variable wake_;     // a job opened, or the pool stops
    std::condition_variable finished_; // a job's last helper returned
    std::vector<Job*> jobs_;           // calls in progress, oldest first
    std::vector<std::thread> threads_;
    unsigned idle_ = 0; // threads not running a task
    bool stop_ = false;
};

} // namespace vds::detail
