// The fragment-list baker (Trapp & Döllner 2008, section 4.1, in one pass:
// per-pixel lists after Yang et al. 2010, "Real-time concurrent linked list
// construction on the GPU", here as a node pool with per-pixel counts), kept
// on the GPU until the sprite is asked for: count per pixel in the raster
// pass, a work-efficient multi-level prefix sum (Blelloch 1990, "Prefix sums
// and their applications") for the column offsets, then scatter and
// per-column sort in compute, into a CSR buffer read back once. When the
// node pool overflows it is grown, then the image is baked in row bands; no
// crossing is ever dropped.
#include <vds/gl/detail/lists.h>

#include <algorithm>
#include <optional>
#include <string>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/gl/shader.h>
#include <vds/gl/detail/bake_setup.h>
#include <vds/gl/detail/dispatch.h>
#include <vds/gl/detail/raster_state.h>

namespace vds::detail {
namespace {

constexpr std::uint64_t kScanChunk = 64; // values an invocation of scan.comp scans
constexpr std::uint64_t kNodeBytes = 16; // lists.frag: depth, key, column, slot
constexpr std::uint64_t kPairBytes = 8;  // a crossing in the fixed places and the sort: depth, key
constexpr GLbitfield kComputeToCompute = GL_SHADER_STORAGE_BARRIER_BIT;
constexpr GLbitfield kComputeToHost = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

std::uint64_t roundUp(std::uint64_t n, std::uint64_t m) { return (n + m - 1) / m * m; }

Buffer makeBuffer(std::uint64_t bytes, const char* what) {
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), GLsizeiptr(std::max<std::uint64_t>(bytes, 4)), nullptr, 0);
    checkGl(what);
    return b;
}

void clearToZero(GLuint buffer, std::uint64_t bytes) {
    const GLuint zero = 0;
    glClearNamedBufferSubData(buffer, GL_R32UI, 0, GLsizeiptr(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

GLint uniform(const Program& p, const char* name) { return glGetUniformLocation(p.id(), name); }

} // namespace

ListsBake::ListsBake(const GlContext& gl, const SpriteGrid& grid, const BakeOptions& options,
                     const GlBakeOptions& glOptions, GlPhaseClock& clock, bool keepBands)
    : gl_(gl), grid_(grid), options_(options), glOptions_(glOptions), clock_(clock), keepBands_(keepBands) {
    {
        const GlPhaseClock::Scope phase(clock, BakePhase::Compile, false);
        const std::string defines = bakeDefines(gl);
        auto compute = [&](const char* key, const char* path, const char* defs) {
            return &gl.program(key, [&] { return buildProgram({{GL_COMPUTE_SHADER, path, ""}}, defs); });
        };
        fill_ = &gl.program("vds.lists.fill", [&] {
            return buildProgram({{GL_VERTEX_SHADER, "vds/bake.vert", ""}, {GL_FRAGMENT_SHADER, "vds/lists.frag", ""}},
                                defines);
        });
        reduceFirst_ = compute("vds.scan.reduce.max", "vds/scan.comp", "#define VDS_SCAN_REDUCE\n#define VDS_SCAN_MAX\n");
        reduce_ = compute("vds.scan.reduce", "vds/scan.comp", "#define VDS_SCAN_REDUCE\n");
        down_ = compute("vds.scan.down", "vds/scan.comp", "");
        scatter_ = compute("vds.lists.scatter", "vds/lists_scatter.comp", "");
        sort_ = compute("vds.lists.sort", "vds/lists_sort.comp", "");
    }
    maxBlock_ = gl.limits().maxStorageBlockBytes;
    // A band's fixed places (16 bytes a column) and the sorted pairs of its
    // first two crossings a column (16 bytes) take up to half a storage
    // block; the node pool's crossings have the other half of the pairs.
    maxBandRows_ = std::uint32_t(std::clamp<std::uint64_t>(maxBlock_ / 32 / grid.width, 1, grid.height));
    const std::uint64_t bandColumns = std::uint64_t(grid.width) * maxBandRows_;
    countsBytes_ = roundUp(bandColumns + 1, kScanChunk) * 4;
    const std::string level = "vds.scan.level";
    for (std::uint64_t blocks = countsBytes_ / 4 / kScanChunk;;) {
        const std::uint64_t sums = roundUp(blocks, kScanChunk);
        scanSums_.push_back(scratch((level + std::to_string(scanSums_.size())).c_str(), sums * 4).id());
        if (blocks == 1) break;
        blocks = sums / kScanChunk;
    }
    counter_ = scratch("vds.lists.counter", 4).id();
    stats_ = scratch("vds.lists.stats", 4).id();
    clearToZero(stats_, 4);
    fbo_ = Framebuffer::create();
    glNamedFramebufferParameteri(fbo_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, GLint(grid.width));
    glNamedFramebufferParameteri(fbo_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, GLint(grid.height));
    if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw GlError("fragment list framebuffer is incomplete");
    // The pool holds the third and later crossings of a column: a pool kept
    // from an earlier bake is used whole, else one a column to begin with.
    std::size_t kept = 0;
    gl.scratchBuffer("vds.lists.nodes", 0, &kept);
    capacity_ = std::min<std::uint64_t>(maxNodes(bandColumns),
                                        std::max<std::uint64_t>(kept / kNodeBytes, bandColumns + 1024));
}

std::uint64_t ListsBake::maxNodes(std::uint64_t columns) const {
    std::uint64_t most = std::min(maxBlock_ / kNodeBytes, (maxBlock_ - 2 * columns * kPairBytes) / kPairBytes);
    if (glOptions_.maxListNodes) most = std::min<std::uint64_t>(most, glOptions_.maxListNodes);
    return std::min<std::uint64_t>(most, 0xfffffff0u - 2 * columns);
}

void ListsBake::allocateNodes() {
    nodes_ = scratch("vds.lists.nodes", capacity_ * kNodeBytes).id();
    if (options_.timings) options_.timings->listNodes = capacity_;
}

void ListsBake::run(MeshView mesh, const std::function<void(GpuBand&)>& take, const GpuMesh* uploaded) {
    std::optional<GpuMesh> draw;
    {
        const GlPhaseClock::Scope phase(clock_, BakePhase::Upload);
        if (!uploaded) draw.emplace(mesh);
        allocateNodes();
    }
    const GpuMesh& drawn = uploaded ? *uploaded : *draw;
    for (std::uint32_t y0 = 0; y0 < grid_.height; y0 += maxBandRows_)
        band(drawn, y0, std::min(grid_.height, y0 + maxBandRows_), take);
    if (options_.timings) options_.timings->bands = bands_;
}

// The band's rasterizing pass: counts, first pairs and pooled nodes.
GLuint ListsBake::raster(const GpuMesh& mesh, std::uint32_t y0, std::uint32_t y1, GLuint counts, GLuint firsts,
                         std::uint64_t scanned) {
    GLuint pooled = 0;
    const GlPhaseClock::Scope phase(clock_, BakePhase::Raster);
    clearToZero(counts, scanned * 4);
    clearToZero(counter_, 4);
    const BakeRasterState state(gl_, grid_, fill_->id());
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, GLint(y0), GLsizei(grid_.width), GLsizei(y1 - y0));
    glUniform1ui(uniform(*fill_, "u_capacity"), GLuint(capacity_));
    glUniform1i(uniform(*fill_, "u_rowBegin"), GLint(y0));
    glUniform1ui(uniform(*fill_, "u_width"), grid_.width);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, counter_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, nodes_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, firsts);
    mesh.draw();
    glMemoryBarrier(GL_ATOMIC_COUNTER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(counter_, 0, sizeof pooled, &pooled);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, 0);
    checkGl("fragment list pass");
    return pooled;
}

// The band's sort: pooled nodes scattered to pairs, each column's crossings
// sorted into `out.crossings`.
void ListsBake::sortBand(GpuBand& out, GLuint firsts, GLuint pooled, std::uint64_t columns) {
    const GLuint counts = out.offsets;
    const std::uint64_t total = out.count;
    const GlPhaseClock::Scope phase(clock_, BakePhase::Sort);
    if (keepBands_) {
        out.ownCrossings = makeBuffer(total * 4, "allocating the sorted crossings");
        out.crossings = out.ownCrossings.id();
    } else {
        out.crossings = scratch("vds.lists.crossings", total * 4).id();
    }
    const GLuint pairs = scratch("vds.lists.pairs", total * kPairBytes).id();
    if (pooled) {
        glUseProgram(scatter_->id());
        glUniform1ui(uniform(*scatter_, "u_nodes"), pooled);
        glUniform1ui(uniform(*scatter_, "u_base"), GLuint(done_));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, nodes_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counts);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, pairs);
        glDispatchCompute(strideGroups(pooled), 1, 1);
        glMemoryBarrier(kComputeToCompute);
    }
    glUseProgram(sort_->id());
    glUniform1ui(uniform(*sort_, "u_columns"), GLuint(columns));
    glUniform1ui(uniform(*sort_, "u_base"), GLuint(done_));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, firsts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, pairs);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, out.crossings);
    glDispatchCompute(strideGroups(columns), 1, 1);
    glMemoryBarrier(kComputeToHost);
    for (GLuint binding = 0; binding < 4; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
    glUseProgram(0);
    checkGl("sorting fragment lists");
}

// Bakes rows [y0, y1); splits them when the node pool cannot hold their crossings.
void ListsBake::band(const GpuMesh& mesh, std::uint32_t y0, std::uint32_t y1,
                     const std::function<void(GpuBand&)>& take) {
    const std::uint64_t columns = std::uint64_t(grid_.width) * (y1 - y0);
    const std::uint64_t scanned = roundUp(columns + 1, kScanChunk);
    Buffer ownCounts;
    if (keepBands_) ownCounts = makeBuffer(scanned * 4, "allocating the column offsets");
    const GLuint counts = keepBands_ ? ownCounts.id() : scratch("vds.lists.counts", countsBytes_).id();
    const GLuint firsts = scratch("vds.lists.firsts", columns * 2 * kPairBytes).id();
    // The crossings past the first two of their column.
    const GLuint pooled = raster(mesh, y0, y1, counts, firsts, scanned);
    if (pooled > capacity_) {
        if (pooled <= maxNodes(columns)) {
            capacity_ = pooled;
            allocateNodes();
            report(options_, "fragment lists: node pool grown to " + std::to_string(capacity_));
            band(mesh, y0, y1, take);
        } else if (y1 - y0 > 1) {
            const std::uint32_t mid = y0 + (y1 - y0) / 2;
            report(options_, "fragment lists: baking rows in bands");
            band(mesh, y0, mid, take);
            band(mesh, mid, y1, take);
        } else {
            throw OutOfMemory("one row of the image has " + std::to_string(pooled) +
                              " crossings, more than a GL buffer holds; lower the resolution");
        }
        return;
    }
    if (done_ + 2 * columns + pooled > 0xffffffffull) throw OutOfMemory("sprite has more than 2^32 - 1 crossings");

    GLuint end = 0; // the band's last offset: done_ + its crossings
    {
        const GlPhaseClock::Scope phase(clock_, BakePhase::Scan);
        scan(counts, columns, done_);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(counts, GLintptr(columns * 4), sizeof end, &end);
        checkGl("reading the band's crossing count");
    }
    const std::uint64_t total = end - done_;
    GpuBand out;
    out.y0 = y0;
    out.y1 = y1;
    out.base = done_;
    out.count = total;
    out.offsets = counts;
    out.ownOffsets = std::move(ownCounts);
    sortBand(out, firsts, pooled, columns);
    done_ = end;
    ++bands_;
    take(out);
    report(options_, "fragment lists: rows " + std::to_string(y1) + " of " + std::to_string(grid_.height));
}

// Exclusive prefix sum of the band's counts into offsets starting at `base`
// (scan.comp): reduce chunk totals level by level, then scan top down.
void ListsBake::scan(GLuint counts, std::uint64_t columns, std::uint64_t base) {
    std::vector<std::uint64_t> chunks{roundUp(columns + 1, kScanChunk) / kScanChunk};
    while (chunks.back() > 1) chunks.push_back((chunks.back() + kScanChunk - 1) / kScanChunk);
    const std::size_t top = chunks.size() - 1; // one chunk
    auto data = [&](std::size_t level) { return level == 0 ? counts : scanSums_[level - 1]; };
    auto groups = [](std::uint64_t n) { return (n + 255) / 256; }; // an invocation a chunk
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, stats_);
    for (std::size_t level = 0; level < top; ++level) {
        const Program& p = level == 0 ? *reduceFirst_ : *reduce_;
        glUseProgram(p.id());
        glUniform1ui(uniform(p, "u_chunks"), GLuint(chunks[level]));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data(level));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, scanSums_[level]);
        dispatchGroups(groups(chunks[level]));
        glMemoryBarrier(kComputeToCompute);
    }
    if (top == 0) { // one chunk: d_S from the reduction all the same
        glUseProgram(reduceFirst_->id());
        glUniform1ui(uniform(*reduceFirst_, "u_chunks"), 1u);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counts);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, scanSums_[0]);
        dispatchGroups(1);
        glMemoryBarrier(kComputeToCompute);
    }
    glUseProgram(down_->id());
    for (std::size_t level = top + 1; level-- > 0;) {
        glUniform1ui(uniform(*down_, "u_chunks"), GLuint(chunks[level]));
        glUniform1ui(uniform(*down_, "u_base"), GLuint(base));
        glUniform1i(uniform(*down_, "u_top"), level == top ? 1 : 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data(level));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, scanSums_[level]); // unread at the top
        dispatchGroups(groups(chunks[level]));
        glMemoryBarrier(kComputeToCompute);
    }
    for (GLuint binding = 0; binding < 3; ++binding) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
    glUseProgram(0);
    checkGl("prefix sum of the column counts");
}

std::uint32_t ListsBake::depthComplexity() const {
    GLuint most = 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(stats_, 0, sizeof most, &most);
    checkGl("reading the depth complexity");
    return most;
}

void bakeLists(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
               const GlBakeOptions& glOptions, GlPhaseClock& clock, std::vector<std::uint32_t>& offsets,
               std::vector<float>& crossings, const GpuMesh* uploaded) {
    const std::size_t columns = std::size_t(grid.width) * grid.height;
    offsets.assign(columns + 1, 0);
    crossings.clear();
    ListsBake lists(gl, grid, options, glOptions, clock, false);
    lists.run(mesh, [&](GpuBand& band) {
        const GlPhaseClock::Scope phase(clock, BakePhase::ReadBack);
        const std::size_t first = std::size_t(band.y0) * grid.width;
        const std::size_t bandColumns = std::size_t(band.y1 - band.y0) * grid.width;
        glGetNamedBufferSubData(band.offsets, 0, GLsizeiptr((bandColumns + 1) * 4), offsets.data() + first);
        crossings.resize(std::size_t(band.base + band.count));
        if (band.count)
            glGetNamedBufferSubData(band.crossings, 0, GLsizeiptr(band.count * 4), crossings.data() + band.base);
        checkGl("reading the fragment lists back");
    }, uploaded);
}

} // namespace vds::detail
