// The GL bakers' shared state handling, and `bakeOnGl` (<vds/gl/bake.h>).
#include "bake_gl.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/bake.h>
#include <vds/detail/bake_common.h>
#include <vds/detail/parallel.h>

namespace vds::detail {
namespace {

bool hasClipControl(const GlContext& gl) {
    const GlInfo& i = gl.info();
    return i.major > 4 || (i.major == 4 && i.minor >= 5);
}


} // namespace

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

namespace {

// Triangles a chunk of `drawableBox`.
constexpr std::size_t kBoxChunk = std::size_t(1) << 16;

// The box of every position, where every index is in range and every
// coordinate finite (the mesh can be drawn before validation); nullopt
// otherwise. Validation's bounds (of the used vertices) equal it unless an
// unused vertex lies outside.
std::optional<Box> drawableBox(MeshView mesh) {
    const std::size_t nv = mesh.positionCount, nt = mesh.triangleCount;
    if (nv == 0 || nt == 0) return std::nullopt;
    const std::size_t chunks = (std::max(nv, nt) + kBoxChunk - 1) / kBoxChunk;
    std::vector<Box> boxes(chunks, Box{mesh.positions[0], mesh.positions[0]});
    std::vector<std::uint8_t> bad(chunks, 0);
    detail::parallelFor(0, std::max(nv, nt), kBoxChunk, [&](std::size_t begin, std::size_t end) {
        Box& box = boxes[begin / kBoxChunk];
        bool wrong = false;
        for (std::size_t i = begin; i < std::min(end, nv); ++i) {
            const glm::vec3 p = mesh.positions[i];
            wrong |= !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            box.lo = glm::min(box.lo, p);
            box.hi = glm::max(box.hi, p);
        }
        for (std::size_t t = begin; t < std::min(end, nt); ++t) {
            const glm::uvec3 tri = mesh.triangles[t];
            wrong |= tri.x >= nv || tri.y >= nv || tri.z >= nv;
        }
        bad[begin / kBoxChunk] = wrong;
    });
    if (std::find(bad.begin(), bad.end(), 1) != bad.end()) return std::nullopt;
    Box all = boxes[0];
    for (const Box& b : boxes) all.lo = glm::min(all.lo, b.lo), all.hi = glm::max(all.hi, b.hi);
    return all;
}

// validateForBake where the GPU counts the axis: the count is issued first,
// in the box of the positions, and validation runs on the host while the GPU
// draws; the count is read back after (recounted in validation's bounds
// where they differ). False where the mesh cannot be drawn before
// validation (an index out of range or a coordinate not finite): then
// validation goes first, and throws.
bool countBesideValidation(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock,
                           ValidatedMesh& out, Axis& axis) {
    const std::optional<Box> box = drawableBox(mesh);
    if (!box) return false;
    BakeOptions untimed = options;
    untimed.timings = nullptr;
    std::optional<PendingLayerCount> pending;
    {
        const GlPhaseClock::Scope phase(clock, BakePhase::Axis, true, false); // timed on the GPU, not waited for
        const CurrentContext current(gl);
        out.drawn.emplace(mesh);
        pending = PendingLayerCount::start(gl, *out.drawn, *box, options.resolution);
    }
    {
        const GlPhaseClock::Scope phase(clock, BakePhase::Validation, false);
        out.report = validateForBake(mesh, untimed);
    }
    const bool ready = pending && out.report.bounds.lo == box->lo && out.report.bounds.hi == box->hi;
    const GlPhaseClock::Scope phase(clock, BakePhase::Axis, !ready);
    const std::optional<AxisChoice> counted =
        ready ? std::optional<AxisChoice>(pending->finish())
              : countLayersOnGl(gl, *out.drawn, out.report.bounds, options.resolution); // the mesh drawn again
    axis = counted ? counted->axis : chooseViewAxis(mesh, out.report, options.resolution).axis; // too large for GL
    return true;
}

} // namespace

// The one validation of every baker (detail::prepareBake), timed on the GL
// bake's clock: the axis count on the GPU's timer where it runs there, and
// then beside validation.
ValidatedMesh validateForBake(const GlContext& gl, MeshView mesh, const BakeOptions& options, GlPhaseClock& clock) {
    ValidatedMesh out;
    Axis axis = options.axis.value_or(Axis::Z);
    const bool gpuCount = !options.axis && countsOnGpu(gl);
    if (!gpuCount || !countBesideValidation(gl, mesh, options, clock, out, axis)) {
        BakeOptions untimed = options;
        untimed.timings = nullptr;
        // Where the CPU counts the axis, validation finds the edges' partners and facings for it.
        MeshFinds finds;
        {
            const GlPhaseClock::Scope phase(clock, BakePhase::Validation, false);
            out.report = validateForBake(mesh, untimed, options.axis || gpuCount ? nullptr : &finds);
        }
        if (!options.axis) {
            const GlPhaseClock::Scope phase(clock, BakePhase::Axis, gpuCount);
            axis = bakeAxis(mesh, out.report, untimed, axisCounter(gl, mesh, options, &out.drawn), finds);
        }
    }
    out.grid = makeGrid(out.report.bounds, axis, options.resolution);
    return out;
}

Buffer uploadBuffer(const void* data, std::size_t bytes, const char* what) {
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::size_t>(bytes, 4)), bytes ? data : nullptr, 0);
    checkGl(what);
    return b;
}

void dispatchGroups(std::uint64_t groups) {
    constexpr std::uint64_t kMax = 65535;
    if (groups <= kMax) {
        glDispatchCompute(GLuint(std::max<std::uint64_t>(groups, 1)), 1, 1);
        return;
    }
    const std::uint64_t rows = (groups + kMax - 1) / kMax;
    if (rows > kMax) throw OutOfMemory("a compute pass of " + std::to_string(groups) + " workgroups is too large");
    glDispatchCompute(GLuint(kMax), GLuint(rows), 1);
}

GLuint strideGroups(std::uint64_t items, std::uint32_t local) {
    return GLuint(std::clamp<std::uint64_t>((items + local - 1) / local, 1, 65535));
}

std::string bakeDefines(const GlContext& gl) { return hasClipControl(gl) ? "#define VDS_CLIP_CONTROL\n" : ""; }

BakeRasterState::BakeRasterState(const GlContext& gl, const SpriteGrid& grid, GLuint program)
    : clipControl_(hasClipControl(gl)) {
    if (clipControl_) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, GLsizei(grid.width), GLsizei(grid.height));
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_CLAMP);
    glFrontFace(GL_CW);
    glUseProgram(program);
    // At bake time, world = mesh coordinates: the grid's own placement.
    glUniformMatrix3fv(glGetUniformLocation(program, "u_placement.matrix"), 1, GL_FALSE, &grid.matrix[0][0]);
    glUniform3fv(glGetUniformLocation(program, "u_placement.position"), 1, &grid.position[0]);
}

BakeRasterState::~BakeRasterState() {
    if (clipControl_) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_MULTISAMPLE);
    glFrontFace(GL_CCW);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Texture makeTexture2D(GLenum format, const SpriteGrid& grid) {
    Texture t = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, format, GLsizei(grid.width), GLsizei(grid.height));
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl("allocating a bake target");
    return t;
}

void report(const BakeOptions& options, const std::string& what) {
    if (options.progress) options.progress(what);
}

} // namespace vds::detail

namespace vds {

BakeMethod chooseBakeMethod(const GlContext& gl, std::string* why) {
    const std::string& renderer = gl.info().renderer;
    const bool software = detail::softwareRenderer(gl);
    if (why)
        *why = software ? "bake method auto: cpu, because GL here is the software renderer " + renderer +
                              " (the CPU baker is faster for a one-shot bake there)"
                        : "bake method auto: lists (GL fragment lists) on the GPU " + renderer;
    return software ? BakeMethod::Cpu : BakeMethod::Lists;
}

Sprite bakeOnGl(const GlContext& gl, MeshView mesh, const BakeOptions& options) {
    if (options.method == BakeMethod::Auto) {
        BakeOptions chosen = options;
        chosen.method = chooseBakeMethod(gl);
        return bakeOnGl(gl, mesh, chosen);
    }
    if (options.method == BakeMethod::Cpu) return bakeCpu(mesh, options);
    const detail::BakeClock clock(options.timings);
    // Validated as bakeToGpu validates: where the GPU counts the axis, while it counts.
    detail::ValidatedMesh v;
    {
        const CurrentContext current(gl);
        detail::GlPhaseClock phases(options.timings);
        v = detail::validateForBake(gl, mesh, options, phases);
        phases.collect();
    }
    // The axis count's upload (if any) is drawn again by the bake.
    return detail::bakeOnGl(gl, {v.report, v.grid}, mesh, options, v.drawn ? &*v.drawn : nullptr);
}

Sprite detail::bakeOnGl(const GlContext& gl, const BakeSetup& setup, MeshView mesh, const BakeOptions& options,
                        const GpuMesh* uploaded) {
    if (options.method == BakeMethod::Cpu) return bakeCpu(setup, mesh, options);
    std::vector<std::uint32_t> offsets;
    std::vector<float> crossings;
    {
        const CurrentContext restore(gl);
        if (options.timings) options.timings->renderer = gl.info().renderer;
        detail::GlPhaseClock phases(options.timings);
        if (options.method == BakeMethod::Peel)
            detail::bakePeel(gl, mesh, setup.grid, options, phases, offsets, crossings, uploaded);
        else
            detail::bakeLists(gl, mesh, setup.grid, options, phases, offsets, crossings, uploaded);
        phases.collect();
    }
    return detail::assembleSprite(setup, options, mesh, std::move(offsets), std::move(crossings));
}

} // namespace vds
