#include <vds/gl/detail/phase_clock.h>

#include <algorithm>

#include <GL/glext.h>

#include <vds/gl/context.h>
#include <vds/gl/detail/context.h>

namespace vds::detail {

void GlPhaseClock::begin(BakePhase phase, bool gpu, bool wait) {
    end();
    if (!timings_) return;
    running_ = true;
    phase_ = phase;
    gpu_ = gpu;
    wait_ = wait;
    start_ = std::chrono::steady_clock::now();
    if (!gpu) return;
    queries_.push_back({phase, Query::create(GL_TIME_ELAPSED), 0.0});
    glBeginQuery(GL_TIME_ELAPSED, queries_.back().query.id());
}

void GlPhaseClock::end() noexcept {
    if (!running_) return;
    running_ = false;
    if (!detail::glUsable()) return;
    if (gpu_) glEndQuery(GL_TIME_ELAPSED);
    if (wait_) glFinish();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (gpu_) queries_.back().wallSeconds = wall;
    BakeTimings::Phase& p = (*timings_)[phase_];
    p.wallSeconds += wall;
    ++p.runs;
}

void GlPhaseClock::collect() {
    end();
    if (!timings_) return;
    for (const Measured& m : queries_) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(m.query.id(), GL_QUERY_RESULT, &ns);
        const double seconds = 1e-9 * double(ns);
        if (seconds < 1e-3 * m.wallSeconds || seconds > m.wallSeconds) continue;
        BakeTimings::Phase& p = (*timings_)[m.phase];
        p.gpuSeconds = std::max(p.gpuSeconds, 0.0) + seconds;
    }
    queries_.clear();
    checkGl("reading the bake's timer queries");
}

} // namespace vds::detail
