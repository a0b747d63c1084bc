// vds: splitting a batch over threads, the one way the library does it.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace vds {

/// Runs body(begin, end) over [0, count) in chunks on `threads` threads (0:
/// one per hardware thread), the calling thread included. Rethrows the first
/// exception a chunk threw.
template <class Body>
void parallelFor(unsigned threads, std::size_t count, std::size_t chunk, const Body& body) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t chunks = (count + chunk - 1) / chunk;
    threads = unsigned(std::min<std::size_t>(threads, chunks));
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    const auto work = [&] {
        try {
            for (std::size_t c; (c = next.fetch_add(1)) < chunks;) body(c * chunk, std::min(count, (c + 1) * chunk));
        } catch (...) {
            const std::lock_guard<std::mutex> lock(errorMutex);
            if (!error) error = std::current_exception();
            next = chunks;
        }
    };
    std::vector<std::thread> pool;
    try {
        for (unsigned k = 1; k < threads; ++k) pool.emplace_back(work);
    } catch (const std::system_error&) {
        // Fewer threads than asked: the ones started and this one do the work.
    }
    work();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

} // namespace vds
