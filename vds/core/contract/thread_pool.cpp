// vds: the library's one thread pool (<vds/detail/thread_pool.h>).
#include <vds/detail/thread_pool.h>

#include <algorithm>
#include <atomic>
#include <new>
#include <system_error>

#include <pthread.h>

namespace vds::detail {

namespace {

// Set when the process's pool is destroyed: a static destructor that splits
// work after that runs it on its own thread. Constant-initialised and
// trivially destroyed, so it is valid through all of static destruction.
std::atomic<bool> sharedPoolGone{false};

} // namespace

/// A call in progress, on its caller's stack.
struct ThreadPool::Job {
    void (*task)(void*);
    void* context;
    unsigned slots;        // helpers that may still take it
    unsigned running = 0;  // helpers running it now
};

ThreadPool* ThreadPool::shared() {
    if (sharedPoolGone.load(std::memory_order_acquire)) return nullptr;
    static ThreadPool pool;
    static const int forkHandlers = pthread_atfork(&ThreadPool::beforeFork, &ThreadPool::afterForkInParent,
                                                   &ThreadPool::afterForkInChild);
    (void)forkHandlers;
    return &pool;
}

// fork() copies the memory of the pool but only the forking thread. Taking
// the lock across it keeps the copy consistent; the child then forgets the
// threads it does not have (never joined; the jobs they ran counted as
// done) and starts its own when a call asks for them.
void ThreadPool::beforeFork() {
    if (ThreadPool* pool = shared()) pool->mutex_.lock();
}

void ThreadPool::afterForkInParent() {
    if (ThreadPool* pool = shared()) pool->mutex_.unlock();
}

void ThreadPool::afterForkInChild() {
    ThreadPool* pool = shared();
    if (!pool) return;
    // Their handles name no thread here (and the C library reuses their
    // stacks): kept where nothing joins or detaches them.
    static std::vector<std::thread>* const forgotten = new std::vector<std::thread>;
    for (std::thread& t : pool->threads_) forgotten->push_back(std::move(t));
    pool->threads_.clear();
    pool->idle_ = 0;
    for (Job* job : pool->jobs_) job->slots = job->running = 0;
    // Made anew, not destroyed: they count as waiters the threads that are
    // gone, and a signal to those would wake no thread here.
    new (&pool->wake_) std::condition_variable;
    new (&pool->finished_) std::condition_variable;
    pool->mutex_.unlock();
}

unsigned ThreadPool::hardwareThreads() {
    static const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    return threads;
}

ThreadPool::~ThreadPool() {
    if (this == shared()) sharedPoolGone.store(true, std::memory_order_release);
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
}

unsigned ThreadPool::size() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return unsigned(threads_.size());
}

void ThreadPool::run(unsigned helpers, void (*task)(void*), void* context) {
    if (helpers == 0) {
        task(context);
        return;
    }
    Job job{task, context, helpers};
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        jobs_.push_back(&job);
        unsigned wanted = 0;
        for (const Job* j : jobs_) wanted += j->slots;
        if (wanted > idle_) startThreads(wanted - idle_);
    }
    for (unsigned k = 0; k < helpers; ++k) wake_.notify_one();
    task(context);
    std::unique_lock<std::mutex> lock(mutex_);
    job.slots = 0; // no helper takes it from here on
    jobs_.erase(std::find(jobs_.begin(), jobs_.end(), &job));
    finished_.wait(lock, [&] { return job.running == 0; });
}

// Under the lock.
void ThreadPool::startThreads(unsigned count) {
    try {
        for (unsigned k = 0; k < count; ++k) {
            threads_.emplace_back([this] { serve(); });
            ++idle_;
        }
    } catch (const std::system_error&) {
        // Fewer threads than asked: each call's caller runs its task anyway.
    }
}

// Under the lock.
ThreadPool::Job* ThreadPool::openJob() const {
    for (Job* job : jobs_)
        if (job->slots > 0) return job;
    return nullptr;
}

void ThreadPool::serve() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        Job* job = nullptr;
        wake_.wait(lock, [&] { return stop_ || (job = openJob()) != nullptr; });
        if (stop_) return;
        --job->slots;
        ++job->running;
        --idle_;
        lock.unlock();
        job->task(job->context);
        lock.lock();
        ++idle_;
        if (--job->running == 0) finished_.notify_all();
    }
}

} // namespace vds::detail
