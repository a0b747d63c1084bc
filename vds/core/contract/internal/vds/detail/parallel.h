// vds: splitting a batch over threads, the one way the library does it, on
// the library's one pool (<vds/detail/thread_pool.h>).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>

#include <vds/detail/thread_pool.h>

namespace vds::detail {

/// Runs body(begin, end) over [0, count) in chunks of `chunk` on at most
/// `threads` threads at once (0: one per hardware thread), the calling
/// thread included; the others are the pool's. Rethrows the first exception
/// a chunk threw (the chunks not yet started are then skipped). `body` may
/// itself call parallelFor.
template <class Body>
void parallelFor(unsigned threads, std::size_t count, std::size_t chunk, const Body& body) {
    if (threads == 0) threads = ThreadPool::hardwareThreads();
    const std::size_t chunks = (count + chunk - 1) / chunk;
    threads = unsigned(std::min<std::size_t>(threads, chunks));
    ThreadPool* const pool = ThreadPool::shared();
    if (threads <= 1 || !pool) {
        for (std::size_t c = 0; c < chunks; ++c) body(c * chunk, std::min(count, (c + 1) * chunk));
        return;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto work = [&] {
        try {
            for (std::size_t c; (c = next.fetch_add(1)) < chunks;) body(c * chunk, std::min(count, (c + 1) * chunk));
        } catch (...) {
            const std::lock_guard<std::mutex> lock(errorMutex);
            if (!error) error = std::current_exception();
            next = chunks;
        }
    };
    pool->run(threads - 1, [](void* w) { (*static_cast<decltype(work)*>(w))(); }, &work);
    if (error) std::rethrow_exception(error);
}

} // namespace vds::detail
