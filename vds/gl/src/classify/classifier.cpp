// vds: the GPU sprite behind the classify contract (<vds/gl/classifier.h>).
#include <vds/gl/classifier.h>


namespace vds {

GpuSpriteClassifier::GpuSpriteClassifier(const GlContext& gl, const Sprite& sprite)
    : gl_(gl), sweepsByColumns_(sweepsByColumns(sprite.grid)),
      summary_("sprite-gpu " + std::to_string(sprite.width()) + " x " + std::to_string(sprite.height()) + " x " +
               std::to_string(sprite.depthComplexity) + " along " + toString(sprite.grid.axis)) {
    const CurrentContext current(gl_);
    sprite_.emplace(sprite, GpuSpriteParts::ColumnsOnly);
    classifier_.emplace(gl_);
    occupancy_.emplace(gl_);
}

GpuSpriteClassifier::~GpuSpriteClassifier() {
    const CurrentContext current(gl_);
    occupancy_.reset();
    classifier_.reset();
    sprite_.reset();
}

std::size_t GpuSpriteClassifier::memoryBytes() const {
    return (std::size_t(sprite_->size().x) * sprite_->size().y + 1) * sizeof(std::uint32_t) +
           sprite_->crossingCount() * sizeof(float) + std::size_t(sprite_->boundary().edgeCount()) * 2 * 16;
}

std::string GpuSpriteClassifier::summary() const { return summary_ + " on " + gl_.info().renderer; }

void GpuSpriteClassifier::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes,
                                         std::uint8_t* labels, const ClassifyOptions& options) const {
    const CurrentContext current(gl_);
    classifier_->classify(*sprite_, PointsView::floats(xyz, count, strideBytes), labels, options);
}

void GpuSpriteClassifier::sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const {
    if (!sweepsByColumns_ || grid.cellCount() > (std::uint64_t(1) << 32)) return Classifier::sweep(grid, cells, options);
    const CurrentContext current(gl_);
    occupancy_->occupancy(*sprite_, grid, cells, options);
}

} // namespace vds
