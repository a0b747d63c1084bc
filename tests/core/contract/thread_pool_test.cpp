// The library's one thread pool and parallelFor on it: every chunk once, the
// threads a call asks for and no more, nested calls, exceptions, and threads
// kept between calls.
#include <vds/detail/thread_pool.h>
#include <vds/detail/parallel.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace vds::detail {
namespace {

// Threads running `body` at once, at most: a gauge raised on entry.
struct Gauge {
    std::atomic<unsigned> now{0}, peak{0};
    void enter() {
        const unsigned n = ++now;
        for (unsigned p = peak.load(); n > p && !peak.compare_exchange_weak(p, n);) {}
    }
    void leave() { --now; }
};

// Waits (yielding) until `count` reaches `target` or two seconds pass.
void awaitCount(const std::atomic<unsigned>& count, unsigned target) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (count.load() < target && std::chrono::steady_clock::now() < until) std::this_thread::yield();
}

TEST(ParallelFor, RunsEveryIndexOnceForAnyThreadsAndChunk) {
    for (unsigned threads : {0u, 1u, 2u, 3u, 8u})
        for (std::size_t chunk : {std::size_t(1), std::size_t(7), std::size_t(1000)}) {
            const std::size_t count = 997;
            std::vector<std::atomic<int>> seen(count);
            detail::parallelFor(threads, count, chunk, [&](std::size_t begin, std::size_t end) {
                ASSERT_LE(end - begin, chunk);
                ASSERT_EQ(begin % chunk, 0u);
                for (std::size_t i = begin; i < end; ++i) ++seen[i];
            });
            for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(seen[i].load(), 1) << threads << " " << chunk << " " << i;
        }
    int calls = 0;
    detail::parallelFor(4, 0, 16, [&](std::size_t, std::size_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

TEST(ParallelFor, GetsTheThreadsItAsksForAndNoMore) {
    // Four tasks that each wait for the others: they all run at once only if
    // the call has four threads, more than this machine may have cores.
    for (unsigned threads : {2u, 4u}) {
        Gauge gauge;
        std::atomic<unsigned> arrived{0};
        detail::parallelFor(threads, 64, 1, [&](std::size_t, std::size_t) {
            gauge.enter();
            ++arrived;
            awaitCount(arrived, threads);
            gauge.leave();
        });
        EXPECT_EQ(gauge.peak.load(), threads);
    }
    Gauge single;
    detail::parallelFor(1, 50, 1, [&](std::size_t, std::size_t) {
        single.enter();
        single.leave();
    });
    EXPECT_EQ(single.peak.load(), 1u);
}

TEST(ParallelFor, NestedCallsFinishWithTheRightSum) {
    // Every outer task splits its own range again, two levels deep, with
    // more threads asked for in all than the pool has idle.
    std::atomic<std::uint64_t> sum{0};
    detail::parallelFor(4, 8, 1, [&](std::size_t outer, std::size_t) {
        detail::parallelFor(3, 6, 1, [&](std::size_t middle, std::size_t) {
            detail::parallelFor(2, 1000, 10, [&](std::size_t begin, std::size_t end) {
                std::uint64_t s = 0;
                for (std::size_t i = begin; i < end; ++i) s += (outer * 6 + middle) * 1000 + i;
                sum += s;
            });
        });
    });
    const std::uint64_t n = 8 * 6 * 1000;
    EXPECT_EQ(sum.load(), n * (n - 1) / 2);
}

TEST(ParallelFor, RethrowsTheFirstExceptionAndStaysUsable) {
    try {
        detail::parallelFor(3, 1000, 1, [&](std::size_t begin, std::size_t) {
            if (begin == 10) throw std::runtime_error("chunk 10");
        });
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "chunk 10");
    }
    // From a nested call on a pool thread, through the outer call.
    try {
        detail::parallelFor(2, 4, 1, [&](std::size_t outer, std::size_t) {
            detail::parallelFor(2, 100, 1, [&](std::size_t inner, std::size_t) {
                if (outer == 3 && inner == 50) throw std::length_error("3/50");
            });
        });
        FAIL() << "no exception";
    } catch (const std::length_error& e) {
        EXPECT_STREQ(e.what(), "3/50");
    }
    EXPECT_THROW(detail::parallelFor(1, 5, 1, [](std::size_t b, std::size_t) { if (b == 3) throw std::out_of_range("3"); }),
                 std::out_of_range);
    std::atomic<std::size_t> total{0};
    detail::parallelFor(3, 100, 1, [&](std::size_t begin, std::size_t) { total += begin; });
    EXPECT_EQ(total.load(), 99u * 100u / 2u);
}

TEST(ThreadPool, KeepsItsThreadsBetweenCalls) {
    ThreadPool* pool = ThreadPool::shared();
    ASSERT_NE(pool, nullptr);
    detail::parallelFor(3, 30, 1, [](std::size_t, std::size_t) {});
    const unsigned kept = pool->size();
    EXPECT_GE(kept, 2u);
    for (int call = 0; call < 200; ++call) {
        std::atomic<unsigned> arrived{0};
        detail::parallelFor(3, 3, 1, [&](std::size_t, std::size_t) {
            ++arrived;
            awaitCount(arrived, 3);
        });
    }
    EXPECT_EQ(pool->size(), kept);
}

TEST(ThreadPool, ServesCallsFromSeveralThreadsAtOnce) {
    std::vector<std::uint64_t> sums(4, 0);
    std::vector<std::thread> callers;
    for (std::size_t c = 0; c < sums.size(); ++c)
        callers.emplace_back([&, c] {
            for (int round = 0; round < 20; ++round) {
                std::atomic<std::uint64_t> s{0};
                detail::parallelFor(2, 500, 7, [&](std::size_t begin, std::size_t end) {
                    for (std::size_t i = begin; i < end; ++i) s += i;
                });
                sums[c] += s;
            }
        });
    for (std::thread& t : callers) t.join();
    for (std::uint64_t s : sums) EXPECT_EQ(s, 20u * (499u * 500u / 2u));
}

TEST(ThreadPool, AnOwnPoolRunsTheTaskOnTheCallerAndHelpers) {
    ThreadPool pool;
    std::atomic<unsigned> runs{0};
    auto task = [&] {
        ++runs;
        awaitCount(runs, 3);
    };
    pool.run(2, [](void* t) { (*static_cast<decltype(task)*>(t))(); }, &task);
    EXPECT_EQ(runs.load(), 3u);
    EXPECT_EQ(pool.size(), 2u);
}

TEST(ThreadPool, AForkedChildStartsItsOwnThreadsAndExits) {
    // The parent's threads exist and each has run a task, so none is still
    // starting at the fork: a thread mid-start holds the sanitizers' thread
    // registry, which a child copies locked (its own threads then hang at
    // their start, as seen once under ASan and load).
    std::atomic<unsigned> started{0};
    detail::parallelFor(3, 3, 1, [&](std::size_t, std::size_t) {
        ++started;
        awaitCount(started, 3);
    });
    const pid_t child = fork();
    ASSERT_NE(child, -1);
    if (child == 0) {
        // Three tasks that wait for each other need three threads here too;
        // exit() then joins the child's own threads at static destruction.
        std::atomic<unsigned> arrived{0};
        Gauge gauge;
        detail::parallelFor(3, 3, 1, [&](std::size_t, std::size_t) {
            gauge.enter();
            ++arrived;
            awaitCount(arrived, 3);
            gauge.leave();
        });
        std::exit(gauge.peak.load() == 3 ? 0 : 1);
    }
    int status = 0;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    pid_t done = 0;
    while ((done = waitpid(child, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (done == 0) {
        kill(child, SIGKILL);
        waitpid(child, &status, 0);
        FAIL() << "the forked child did not finish";
    }
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
}

} // namespace
} // namespace vds::detail
