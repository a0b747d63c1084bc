// vds: `Method::SpriteGpu` as a `Classifier` (<vds/classify.h>): a sprite
// uploaded to a GL context, points classified by `GpuClassifier`, grids
// swept by `GpuOccupancy` — the same answers as the CPU sprite.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <vds/classify.h>
#include <vds/gl/context.h>
#include <vds/gl/occupancy.h>
#include <vds/gl/sprite.h>
#include <vds/sprite.h>

namespace vds {

/// Belongs to `gl`, which must outlive it; every call (and the destructor)
/// makes `gl` current and restores the caller's context. Not thread safe:
/// one thread at a time.
class GpuSpriteClassifier final : public Classifier {
public:
    /// Uploads the sprite's columns (and its boundary edges) to `gl`.
    GpuSpriteClassifier(const GlContext& gl, const Sprite& sprite);
    ~GpuSpriteClassifier() override;

    Method method() const override { return Method::SpriteGpu; }
    /// Bytes of GL memory the sprite's columns and boundary edges take.
    std::size_t memoryBytes() const override;
    std::string summary() const override;
    const GpuSprite& gpuSprite() const { return *sprite_; }
    const GlContext& context() const { return gl_; }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;
    /// The GPU column sweep when the sprite's axes are aligned with the
    /// grid's (`sweepsByColumns`, <vds/sprite.h>), else cell centres.
    void sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const override;

private:
    const GlContext& gl_;
    bool sweepsByColumns_ = true;
    std::string summary_;
    std::optional<GpuSprite> sprite_;
    mutable std::optional<GpuClassifier> classifier_;
    mutable std::optional<GpuOccupancy> occupancy_;
};

} // namespace vds
