// vds: certified classification on the GPU — `Method::CertifiedGpu`, the
// exact classifier's answers on every point, most of them found by a
// compute shader.
//
// Design. The CPU `CertifiedClassifier` (<vds/certified.h>) bakes, for every
// texel column of a grid over the mesh's box (a sprite's grid), the
// "uncertain bands" {lo, hi, windingAbove}: between two bands the surface
// is provably absent, so every depth there has the winding number the bake
// counted at the texel centre. `GpuCertifiedBands` uploads those bands to
// GL beside the grid's placement; shaders/vds/certified.glsl's
// `vdsContainsCertain` answers a point from them (1 inside, 0 outside) or
// says it is unsure (in a band, on the box's boundary, not finite, or a
// rule the mesh does not certify).
//
// `GpuCertifiedClassifier` runs that test over a batch of points in a
// compute program (certified.comp): certain points get their label there,
// unsure ones are marked and appended, with an atomic counter, to a compact
// list (their bits and index). The host reads back only that list, answers
// it with the exact classifier on the library's threads (`ClassifyOptions::
// threads`), and writes those labels in: into the host array directly, or,
// for GL buffers, with a small scatter pass. Two batches are in flight: the
// host answers one batch's list while the GPU classifies the next. Meshes or rules the bands do
// not certify (a mesh that is not closed, the winding rules on one that is
// not consistently oriented: the generalized winding number of an open
// mesh) go to the exact classifier whole, as on the CPU. So the labels
// equal `ExactClassifier(mesh, axis)`'s everywhere, and `options.stats`
// counts the points the GPU answered (`certain`) and the exact classifier
// (`exact`). Occupancy grids go through the same path (the default
// `Classifier::sweep` over cell centres), so they are exact too.
//
// Where the GLSL texel lookup rounds differently from the C++ one: see
// certified.glsl (the bands' 1/64-texel widening covers it).
//
// The GL rule of <vds/gl/context.h> holds: both classes belong to the
// context they are made in; the classifier makes it current for every call
// and restores the caller's. Not thread safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <vds/certified.h>
#include <vds/classify.h>
#include <vds/gl/context.h>
#include <vds/gl/objects.h>

namespace vds {

/// A certified classifier's bands in GL: two shader storage buffers and the
/// uniforms of certified.glsl's `VdsCertified`.
class GpuCertifiedBands {
public:
    /// Uploads `certified`'s bands (`CertifiedClassifier::bands`) to the
    /// context current on the calling thread. Throws `GlError` with none
    /// current, `OutOfMemory` when a buffer exceeds one storage block.
    explicit GpuCertifiedBands(const CertifiedClassifier& certified);
    GpuCertifiedBands(GpuCertifiedBands&&) noexcept = default;
    GpuCertifiedBands& operator=(GpuCertifiedBands&&) noexcept = default;

    /// Binds the offsets to shader storage binding `offsetsBinding` and the
    /// bands to `bandsBinding` (the shader's VDS_CERTIFIED_OFFSETS_BINDING
    /// and VDS_CERTIFIED_BANDS_BINDING) and sets, in `program` (in use or
    /// not), the `VdsCertified` uniform `name` (e.g. "u_certified").
    /// Throws a one-line `GlError` unless the context the bands were made
    /// in is current on the thread they were made on.
    void setUniforms(GLuint program, const std::string& name, GLuint offsetsBinding, GLuint bandsBinding) const;
    /// Bit (1 << Rule) for each rule the bands answer (`CertifiedBands::certifiedRules`).
    std::uint8_t certifiedRules() const { return rules_; }
    /// Bytes of GL memory the two buffers take.
    std::size_t bytes() const { return bytes_; }

private:
    ContextStamp context_;
    Buffer offsets_, bands_;
    SpriteGrid grid_;
    Box box_;
    int depthAxis_ = 2;
    std::uint8_t rules_ = 0;
    std::size_t bytes_ = 0;
};

/// `Method::CertifiedGpu` (see the preface). Belongs to `gl`, which must
/// outlive it.
class GpuCertifiedClassifier final : public Classifier {
public:
    /// Builds the CPU certified classifier (`options`; `threads` for the
    /// build) and uploads its bands to `gl`. Host arrays and GL buffers go
    /// to the GPU `batchPoints` at a time (a power of two, at least 1024,
    /// lowered to fit one storage block); GL memory for two batches is
    /// kept (2 x 33 bytes a point). Throws as `CertifiedClassifier`, and `GlError`.
    GpuCertifiedClassifier(const GlContext& gl, MeshView mesh, const CertifiedOptions& options = {},
                           std::size_t batchPoints = std::size_t(1) << 22);
    ~GpuCertifiedClassifier() override;

    Method method() const override { return Method::CertifiedGpu; }
    /// GL memory of the bands and the batch buffers, plus the host memory
    /// of the exact classifier behind them.
    std::size_t memoryBytes() const override;
    std::string summary() const override;
    /// The CPU classifier: its bands, grid and exact classifier.
    const CertifiedClassifier& certified() const { return *cpu_; }
    const GpuCertifiedBands& bands() const { return *bands_; }

    using Classifier::classify;
    /// GL buffers to GL buffers, in the layouts of `GpuClassifier`'s GL
    /// call (<vds/gl/sprite.h>): `points` holds `count` packed vec3 (12
    /// bytes each) from offset 0, `labels` receives one byte a point, 1 or
    /// 0, written as 32-bit words (4 * ceil(count / 4) bytes, the tail
    /// word's unused bytes 0). Waits for the GPU once a batch (the unsure
    /// points are read back, answered on the host while the GPU classifies
    /// the next batch, and written in); returns
    /// with the labels written, a glMemoryBarrier (all bits) issued.
    /// `options.stats` as for host arrays.
    void classify(GLuint points, std::size_t count, GLuint labels, const ClassifyOptions& options = {}) const;

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;

private:
    /// GL buffers to GL buffers where the bands certify nothing: every point exact on the host.
    void classifyAllExact(GLuint points, std::size_t count, GLuint labels, const ClassifyOptions& options) const;
    struct Batches;
    const GlContext& gl_;
    std::unique_ptr<CertifiedClassifier> cpu_;
    std::unique_ptr<GpuCertifiedBands> bands_;
    std::unique_ptr<Batches> batches_;
};

} // namespace vds
