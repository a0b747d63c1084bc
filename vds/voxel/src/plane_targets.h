// vds::voxel internal: the casters' full-screen draws into plane targets,
// timed (plane_targets.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <GL/gl.h>

#include <vds/gl/objects.h>

namespace vds::voxel::detail {

/// What one draw cost: GL_TIME_ELAPSED, and the wall clock to glFinish.
struct DrawTimes {
    double gpuMilliseconds = 0.0;
    double wallMilliseconds = 0.0;
};

/// Draws the bound vertex array's first triangle (a full-screen triangle)
/// twice, timing the second: drivers compile shader variants at their first
/// draw (llvmpipe does), which is no part of a frame's cost. `what` names the
/// pass in GL errors.
DrawTimes timedFullScreenDraw(const char* what);

/// The colour targets of the casters' full-screen draws (a receiver plane,
/// a view): one 2D texture of each format, `width` x `height`, attached in
/// order to one framebuffer that draws into all of them.
class PlaneTargets {
public:
    /// Throws `GlError` naming `what` if the framebuffer is incomplete.
    PlaneTargets(std::initializer_list<GLenum> formats, GLsizei width, GLsizei height, const char* what);
    const Texture& operator[](std::size_t k) const { return targets_[k]; }
    /// Binds the framebuffer and the viewport and puts `program` in use,
    /// for the caller's uniforms.
    void use(GLuint program) const;
    /// `timedFullScreenDraw`, then no vertex array, program or framebuffer
    /// bound and no texture on units 0 and 1 (those the casters bind).
    DrawTimes draw(const char* what) const;

private:
    std::vector<Texture> targets_;
    Framebuffer fbo_;
    VertexArray vao_;
    GLsizei width_, height_;
};

/// Seconds since `start` (steady clock), for build timings.
double secondsSince(std::uint64_t startNanoseconds);
std::uint64_t nowNanoseconds();

} // namespace vds::voxel::detail
