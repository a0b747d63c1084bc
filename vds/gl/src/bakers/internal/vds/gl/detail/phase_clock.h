// vds::gl internal: the phases of a GL bake timed on the host and by GL's
// timer queries (phase_clock.cpp), for every baker and the axis count.
#pragma once

#include <chrono>
#include <vector>

#include <vds/bake.h>
#include <vds/gl/objects.h>

namespace vds::detail {

/// Times the phases of a GL bake into `timings`, if set (see `BakeTimings`):
/// host wall time from a phase's start until GL has finished its commands
/// (glFinish at the phase's end), and GL_TIME_ELAPSED queries around them.
/// Without timings every call does nothing, so a plain bake never waits.
/// One phase runs at a time (GL allows one active timer query): `begin`
/// ends the running one. A query's time is dropped when it is longer than
/// its phase's wall time or below a thousandth of it, which a working timer
/// never reports (llvmpipe: about 0 for compute passes).
class GlPhaseClock {
public:
    explicit GlPhaseClock(BakeTimings* timings) noexcept : timings_(timings) {}
    ~GlPhaseClock() { end(); }
    GlPhaseClock(const GlPhaseClock&) = delete;
    GlPhaseClock& operator=(const GlPhaseClock&) = delete;

    /// Starts `phase`; `gpu` = false for host work (no timer query). Its
    /// end waits for the GPU, unless `wait` is false (work issued to run
    /// beside the host's next phase: its wall is the issuing, its GPU time
    /// the timer's).
    void begin(BakePhase phase, bool gpu = true, bool wait = true);
    /// Ends the running phase, if any.
    void end() noexcept;
    /// Adds the GPU times of the finished phases (waits for their queries).
    void collect();

    /// One phase for the scope.
    class Scope {
    public:
        Scope(GlPhaseClock& clock, BakePhase phase, bool gpu = true, bool wait = true) : clock_(clock) {
            clock.begin(phase, gpu, wait);
        }
        ~Scope() { clock_.end(); }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        GlPhaseClock& clock_;
    };

private:
    BakeTimings* timings_;
    bool running_ = false;
    bool gpu_ = false;
    bool wait_ = true;
    BakePhase phase_ = BakePhase::Validation;
    std::chrono::steady_clock::time_point start_;
    struct Measured {
        BakePhase phase;
        Query query;
        double wallSeconds;
    };
    std::vector<Measured> queries_;
};

} // namespace vds::detail
