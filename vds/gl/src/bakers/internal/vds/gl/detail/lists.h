// vds::gl internal: the fragment-list bake on the GPU (lists.cpp), shared by
// the host path (vds::bake, BakeMethod::Lists) and vds::bakeToGpu.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <vds/bake.h>
#include <vds/gl/bake.h>
#include <vds/gl/context.h>
#include <vds/gl/detail/phase_clock.h>
#include <vds/gl/mesh.h>
#include <vds/gl/objects.h>

namespace vds::detail {

/// Rows [y0, y1) of a sprite's columns on the GPU, in CSR form (see `Sprite`).
struct GpuBand {
    std::uint32_t y0 = 0, y1 = 0;
    std::uint64_t base = 0;  ///< crossings in the rows above the band: its first offset
    std::uint64_t count = 0; ///< crossings in the band
    /// (y1 - y0) * width + 1 uint32 offsets (more may follow: padding), those
    /// of the whole sprite: the first is `base`, the last `base + count`.
    GLuint offsets = 0;
    /// `count` encoded crossings (float bits, see encodeCrossing), column after column.
    GLuint crossings = 0;
    /// The buffers behind `offsets` and `crossings` when the bake keeps its
    /// bands; else those are the context's scratch buffers, valid until the
    /// next band.
    Buffer ownOffsets, ownCrossings;
};

/// Bakes with per-pixel fragment lists, keeping everything on the GPU: one
/// raster pass counts crossings per pixel, puts the first two of each pixel
/// in fixed places and the rest in a node pool; a GPU prefix sum makes the
/// counts column offsets; compute passes scatter the pooled crossings into
/// their columns and sort each column. When the pool overflows it is grown
/// to the exact need and the pass repeated; past what one GL buffer holds,
/// the image is baked in row bands. Scratch space is the context's
/// (`GlContext::scratchBuffer`), kept for the next bake. Needs `gl` current
/// throughout.
class ListsBake {
public:
    /// `keepBands`: each band's columns in buffers of its own, which `take`
    /// may keep; else in scratch buffers, to be read before the next band.
    ListsBake(const GlContext& gl, const SpriteGrid& grid, const BakeOptions& options,
              const GlBakeOptions& glOptions, GlPhaseClock& clock, bool keepBands);
    ListsBake(const ListsBake&) = delete;
    ListsBake& operator=(const ListsBake&) = delete;

    /// Bakes the (validated) mesh, handing each finished band to `take`, the
    /// top rows first; `take` may keep the band's buffers. `uploaded`: the
    /// mesh in GL already (else it is uploaded here).
    void run(MeshView mesh, const std::function<void(GpuBand&)>& take, const GpuMesh* uploaded = nullptr);
    /// d_S over the bands baked so far (reads one number back from GL).
    std::uint32_t depthComplexity() const;
    /// Crossings baked so far.
    std::uint64_t crossings() const { return done_; }

private:
    void band(const GpuMesh& mesh, std::uint32_t y0, std::uint32_t y1, const std::function<void(GpuBand&)>& take);
    GLuint raster(const GpuMesh& mesh, std::uint32_t y0, std::uint32_t y1, GLuint counts, GLuint firsts,
                  std::uint64_t scanned);
    void sortBand(GpuBand& out, GLuint firsts, GLuint pooled, std::uint64_t columns);
    void allocateNodes();
    /// The most pooled crossings a band of `columns` may have (buffer limits, options).
    std::uint64_t maxNodes(std::uint64_t columns) const;
    void scan(GLuint counts, std::uint64_t columns, std::uint64_t base);
    const Buffer& scratch(const char* key, std::uint64_t bytes) const { return gl_.scratchBuffer(key, bytes); }

    const GlContext& gl_;
    const SpriteGrid& grid_;
    const BakeOptions& options_;
    const GlBakeOptions& glOptions_;
    GlPhaseClock& clock_;
    const Program* fill_ = nullptr;
    const Program* reduceFirst_ = nullptr;
    const Program* reduce_ = nullptr;
    const Program* down_ = nullptr;
    const Program* scatter_ = nullptr;
    const Program* sort_ = nullptr;
    bool keepBands_;
    std::uint64_t maxBlock_ = 0;    ///< GlLimits::maxStorageBlockBytes
    std::uint32_t maxBandRows_ = 0;
    std::uint64_t countsBytes_ = 0; ///< a band's counts, padded to whole scan blocks
    std::uint64_t capacity_ = 0;    ///< crossings the node pool holds
    std::uint64_t done_ = 0;
    std::uint32_t bands_ = 0;
    GLuint nodes_ = 0, counter_ = 0, stats_ = 0;
    std::vector<GLuint> scanSums_; ///< the chunk totals of each scan level above the counts
    Framebuffer fbo_;
};

/// The fragment-list bake behind bakeOnGl(): fills the CSR layers of `grid`
/// on `gl` (current), timing its phases on `clock`. `uploaded`: the mesh
/// already in GL (the axis count's), or null to upload it.
void bakeLists(const GlContext& gl, MeshView mesh, const SpriteGrid& grid, const BakeOptions& options,
               const GlBakeOptions& glOptions, GlPhaseClock& clock, std::vector<std::uint32_t>& offsets,
               std::vector<float>& crossings, const GpuMesh* uploaded = nullptr);

} // namespace vds::detail
