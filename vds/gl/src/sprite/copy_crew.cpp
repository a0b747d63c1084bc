#include "copy_crew.h"

#include <algorithm>
#include <cstring>
#include <system_error>

namespace vds::detail {

namespace {

// Where slice `k` of `n` equal slices of [0, bytes) starts.
std::size_t sliceStart(std::size_t bytes, unsigned k, unsigned n) { return bytes / n * k + std::min<std::size_t>(k, bytes % n); }

} // namespace

CopyCrew::CopyCrew(unsigned threads) {
    try {
        for (unsigned k = 1; k < std::max(1u, threads); ++k) threads_.emplace_back([this, k] { work(k); });
    } catch (const std::system_error&) {
        // Fewer threads than asked: the slices are cut for those started.
    }
    slices_ = unsigned(threads_.size()) + 1;
}

CopyCrew::~CopyCrew() {
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : threads_) t.join();
}

void CopyCrew::copy(void* dst, const void* src, std::size_t bytes) {
    const unsigned n = slices_;
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        dst_ = static_cast<char*>(dst);
        src_ = static_cast<const char*>(src);
        bytes_ = bytes;
        finished_ = 0;
        ++job_;
    }
    start_.notify_all();
    std::memcpy(dst, src, sliceStart(bytes, 1, n)); // slice 0: the caller's
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return finished_ == n - 1; });
}

void CopyCrew::work(unsigned slice) {
    std::uint64_t seen = 0;
    for (;;) {
        char* dst = nullptr;
        const char* src = nullptr;
        std::size_t bytes = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            start_.wait(lock, [&] { return stop_ || job_ != seen; });
            if (stop_) return;
            seen = job_;
            dst = dst_;
            src = src_;
            bytes = bytes_;
        }
        const unsigned n = slices_;
        const std::size_t begin = sliceStart(bytes, slice, n), end = sliceStart(bytes, slice + 1, n);
        std::memcpy(dst + begin, src + begin, end - begin);
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            ++finished_;
        }
        done_.notify_one();
    }
}

} // namespace vds::detail
