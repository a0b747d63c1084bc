// vds: threads kept for copying large blocks between host memory and GL's
// mapped staging buffers (GpuClassifier's host arrays).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace vds::detail {

/// Copies a block on several threads that are started once and wait between
/// copies: a classification of host arrays copies two blocks a batch, and
/// starting threads for each (tens of microseconds a thread) cost the host
/// as much as the copy of a few MiB. Each copy splits its block into equal
/// slices, one a thread, the caller's included. Only host memory is touched:
/// no GL call is made from these threads. Not thread safe.
class CopyCrew {
public:
    /// `threads` in all, the caller's included (at least 1).
    explicit CopyCrew(unsigned threads);
    ~CopyCrew();
    CopyCrew(const CopyCrew&) = delete;
    CopyCrew& operator=(const CopyCrew&) = delete;

    /// memcpy(dst, src, bytes) on the crew; returns when every slice is copied.
    void copy(void* dst, const void* src, std::size_t bytes);

private:
    void work(unsigned slice);

    std::mutex mutex_;
    std::condition_variable start_, done_;
    std::vector<std::thread> threads_;
    unsigned slices_ = 1; // threads started, the caller's included: set before the first copy
    char* dst_ = nullptr;
    const char* src_ = nullptr;
    std::size_t bytes_ = 0;
    std::uint64_t job_ = 0;   // the copy being made, counted from 1
    unsigned finished_ = 0;   // slices of this copy done by the crew's threads
    bool stop_ = false;
};

} // namespace vds::detail
