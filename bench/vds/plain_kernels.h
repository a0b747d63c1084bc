// vds_bench's yardsticks: the plainest GL compute kernels over the very
// buffers vds's classifier reads, timed in the same run, so that each GPU
// figure is printed beside what this GPU does with the same arrays.
//  - parity: four points an invocation (the least that writes whole label
//    words), the column walked, no rule or boundary code, no grid-stride
//    loop: the kernel a GPU programmer would write first.
//  - generalized winding, brute force: the same, plus every boundary edge's
//    solid angle for every point read straight from the storage buffer, no
//    tree, no shared memory: the floor vds's program must not fall below.
// Both give the CPU's labels (the same arithmetic, vpt.glsl), which the
// bench checks.
#pragma once

#include <cstddef>
#include <functional>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/sprite.h>

namespace vds::bench {

/// A form of the plain parity kernel: the columns read through buffer
/// textures (`texel`: the texture cache) instead of storage buffers, and one
/// point an invocation with a 32-bit label (`onePoint`: labels take 4 bytes a
/// point) instead of four with one label word. Measured side by side to
/// find what holds GL below a plain CUDA kernel on random points.
struct PlainForm {
    bool texel = false;
    bool onePoint = false;
};

class PlainKernels {
public:
    explicit PlainKernels(const GlContext& gl);
    /// Labels (one byte a point, four a word) of `count` points (12 bytes
    /// each in `points`) against the sprite's columns by the parity rule.
    void parity(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels) const;
    /// The same by the generalized winding rule, the boundary term summed
    /// over every edge.
    void generalizedWinding(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels) const;
    /// `parity` in another form (its program compiled on first use).
    void parity(const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels, PlainForm form) const;

private:
    void run(const Program& program, const GpuSprite& sprite, GLuint points, std::size_t count, GLuint labels,
             bool onePoint = false) const;
    const GlContext* gl_ = nullptr;
    const Program* parity_ = nullptr;
    const Program* gwn_ = nullptr;
};

/// Runs `dispatch` (GL commands, waited for with glFinish) until `seconds`
/// have passed: a GPU measured straight after CPU work runs at its idle
/// clock (1.3 against 6.2-6.7 G points/s measured on an H200 for the same
/// call), so every timed figure is preceded by this.
void warmUp(const std::function<void()>& dispatch, double seconds);

} // namespace vds::bench
