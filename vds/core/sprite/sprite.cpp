// Trapp & Döllner 2008, section 3.2: the volumetric parity test, on the CPU.
// The arithmetic mirrors shaders/vds/vpt.glsl step for step (no fused
// multiply-adds, same summation order), so C++ and GLSL answers are identical.
#include <vds/sprite.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <thread>

#include <sys/mman.h>

#include <glm/matrix.hpp>

#include <vds/error.h>
#include <vds/detail/aligned_axes.h>
#include <vds/detail/parallel.h>

#include <vds/detail/sprite_winding.h>
#include <vds/detail/antipodal.h>
#include <vds/detail/vpt.h>

namespace vds {

bool Sprite::contains(const glm::vec3& world, Rule rule) const {
    if (detail::needsBoundaryTerm(*this, rule)) return detail::containsGeneralizedWinding(*this, world);
    detail::requireBoundaryKnown(*this, rule);
    const glm::vec3 t = grid.toTexture(world);
    const std::ptrdiff_t column = detail::columnOf(grid, t);
    if (column < 0) return false;
    return detail::testColumn(crossings.data() + offsets[std::size_t(column)],
                      crossings.data() + offsets[std::size_t(column) + 1], t.z, rule);
}

void Sprite::transform(const glm::mat4& model) {
    const glm::mat3 a(model);
    const glm::vec3 b(model[3]);
    const float det = glm::determinant(a);
    if (!(std::isfinite(det) && det != 0.0f) || model[0][3] != 0.0f || model[1][3] != 0.0f || model[2][3] != 0.0f ||
        model[3][3] != 1.0f)
        throw InvalidArgument("sprite transform must be affine and invertible");
    grid.matrix = grid.matrix * glm::inverse(a);
    grid.position = a * grid.position + b;
}

std::size_t Sprite::memoryBytes() const {
    return offsets.size() * sizeof(std::uint32_t) + crossings.size() * sizeof(float);
}

std::size_t Sprite::denseBytes() const {
    return std::size_t(grid.width) * grid.height * std::max<std::uint32_t>(1, depthComplexity) * sizeof(float);
}

namespace {
void checkDistance(const SpriteDistance& distance) {
    if (distance.empty()) return;
    const Grid& g = distance.grid;
    for (int a = 0; a < 3; ++a)
        if (g.dims[a] == 0 || g.dims[a] > kMaxDistanceResolution)
            throw FormatError("sprite distance grid size " + std::to_string(g.dims[a]) + " is out of range");
    if (g.first != glm::uvec3(0u) || (g.whole != glm::uvec3(0u) && g.whole != g.dims))
        throw FormatError("sprite distance grid is a slab");
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(g.box.lo[a]) || !std::isfinite(g.box.hi[a]) || !(g.box.lo[a] < g.box.hi[a]))
            throw FormatError("sprite distance grid box is empty or not finite");
    if (distance.cells.size() != g.cellCount())
        throw FormatError("sprite distance grid holds " + std::to_string(distance.cells.size()) + " cells, not " +
                          std::to_string(g.cellCount()));
    for (float d : distance.cells)
        if (!std::isfinite(d)) throw FormatError("sprite distance grid holds a value that is not finite");
}
} // namespace

void Sprite::checkConsistent() const {
    const std::size_t columns = std::size_t(grid.width) * grid.height;
    if (grid.width == 0 || grid.height == 0 || grid.width > kMaxResolution || grid.height > kMaxResolution)
        throw FormatError("sprite size " + std::to_string(grid.width) + "x" + std::to_string(grid.height) +
                          " is out of range");
    if (offsets.size() != columns + 1) throw FormatError("sprite offsets do not match its size");
    if (offsets.front() != 0 || offsets.back() != crossings.size())
        throw FormatError("sprite offsets do not match its crossing count");
    std::uint32_t most = 0;
    for (std::size_t c = 0; c < columns; ++c) {
        if (offsets[c + 1] < offsets[c]) throw FormatError("sprite offsets decrease at column " + std::to_string(c));
        most = std::max(most, offsets[c + 1] - offsets[c]);
        float previous = 0.0f;
        for (std::uint32_t k = offsets[c]; k < offsets[c + 1]; ++k) {
            const float d = std::fabs(crossings[k]);
            if (!(d >= 0.0f && d <= 1.0f)) throw FormatError("sprite depth out of [0,1] at column " + std::to_string(c));
            if (d < previous) throw FormatError("sprite column " + std::to_string(c) + " is not sorted by depth");
            previous = d;
        }
    }
    if (most != depthComplexity)
        throw FormatError("sprite depth complexity " + std::to_string(depthComplexity) + " disagrees with its columns (" +
                          std::to_string(most) + ")");
    for (int k = 0; k < 9; ++k)
        if (!std::isfinite(grid.matrix[k / 3][k % 3])) throw FormatError("sprite matrix is not finite");
    if (!std::isfinite(grid.position.x + grid.position.y + grid.position.z))
        throw FormatError("sprite position is not finite");
    checkDistance(distance);
}

namespace detail {
namespace {
constexpr std::size_t kHugePage = std::size_t(1) << 21;
} // namespace

void PackedTable::Free::operator()(float* p) const { std::free(p); }

PackedTable::PackedTable(const Sprite& sprite, unsigned threads) {
    const std::size_t columns = sprite.offsets.size() - 1;
    std::size_t deep = 0;
    for (std::size_t c = 0; c < columns; ++c) deep += sprite.offsets[c + 1] - sprite.offsets[c] > 4;
    width_ = double(deep) > kWideShare * double(columns) ? 8 : 4;
    const std::size_t bytes = (columns * width_ * sizeof(float) + kHugePage - 1) / kHugePage * kHugePage;
    table_.reset(static_cast<float*>(std::aligned_alloc(kHugePage, bytes)));
    if (!table_) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(table_.get(), bytes, MADV_HUGEPAGE); // advice only: without huge pages the table works as well
#endif
    float* table = table_.get();
    const unsigned width = width_;
    detail::parallelFor(threads, columns, std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
            const std::uint32_t first = sprite.offsets[c], n = sprite.offsets[c + 1] - first;
            float* record = table + c * width;
            for (std::uint32_t k = 0; k < width; ++k) record[k] = k < n ? sprite.crossings[first + k] : kPadding;
            if (n > width) record[width - 1] = kMore;
        }
    });
}
} // namespace detail

namespace {

// Where a point falls, without branches: its column (0 when it is outside
// the box, so the record can be read anyway), its texture depth, and whether
// it is inside. The same answers as columnOf: floor(x) lies in [0, w) exactly
// when x does, and then floor is the truncation.
struct Located {
    std::uint32_t column;
    float depth;
    bool inBox;
};

inline Located locate(const SpriteGrid& grid, float s, float t, float r) {
    const float x = s * float(grid.width), y = t * float(grid.height);
    const bool in = (r >= 0.0f) & (r <= 1.0f) & (x >= 0.0f) & (x < float(grid.width)) & (y >= 0.0f) &
                    (y < float(grid.height));
    const std::uint32_t column = std::uint32_t(in ? y : 0.0f) * grid.width + std::uint32_t(in ? x : 0.0f);
    return {column, r, in};
}

// A sprite whose s, t and r follow the world axes of view `View`'s
// permutation (detail::alignedAxes: as baked along `View`, or turned onto
// it by quarter turns): texture coordinates are one product each. The general
// product adds zeros to it, which changes at most the sign of a zero result
// (the same column and answer) or turns an infinite coordinate elsewhere into
// NaN (outside the box either way).
template <Axis View> struct AxisAligned {
    glm::vec3 scale;  // the matrix entries of s, t and r
    glm::vec3 origin; // P_S along their world axes

    static bool applies(const SpriteGrid& grid, AxisAligned& out) {
        const glm::ivec3 p = axisPermutation(View);
        if (detail::alignedAxes(grid) != p) return false;
        out = {{grid.matrix[p.x][0], grid.matrix[p.y][1], grid.matrix[p.z][2]},
               {grid.position[p.x], grid.position[p.y], grid.position[p.z]}};
        return true;
    }
    Located operator()(const SpriteGrid& grid, const float* q) const {
        // axisPermutation(View), spelled out so that the indices are constants.
        constexpr int s = View == Axis::Z ? 0 : View == Axis::X ? 1 : 2;
        constexpr int t = View == Axis::Z ? 1 : View == Axis::X ? 2 : 0;
        constexpr int r = View == Axis::Z ? 2 : View == Axis::X ? 0 : 1;
        return locate(grid, scale.x * (q[s] - origin.x), scale.y * (q[t] - origin.y), scale.z * (q[r] - origin.z));
    }
};

struct General {
    Located operator()(const SpriteGrid& grid, const float* q) const {
        const glm::vec3 t = grid.toTexture({q[0], q[1], q[2]});
        return locate(grid, t.x, t.y, t.z);
    }
};

// Packed-table classification of points [begin, end), software-pipelined:
// locate a batch and prefetch its records, then answer the batch located
// before it, so each record has a whole batch's work to arrive.
template <unsigned Width, class Locate>
void classifyPacked(const Sprite& sprite, const float* table, const Locate& where, const char* xyz,
                    std::size_t strideBytes, std::uint8_t* labels, Rule rule, std::size_t begin, std::size_t end) {
    constexpr std::size_t kBatch = 64;
    Located at[2][kBatch];
    const auto locateBatch = [&](std::size_t base, Located* out) {
        const std::size_t n = std::min(kBatch, end - base);
        for (std::size_t i = 0; i < n; ++i) {
            float q[3];
            std::memcpy(q, xyz + (base + i) * strideBytes, sizeof q);
            out[i] = where(sprite.grid, q);
            __builtin_prefetch(table + std::size_t(out[i].column) * Width);
        }
    };
    const auto answerBatch = [&](std::size_t base, const Located* in) {
        const std::size_t n = std::min(kBatch, end - base);
        for (std::size_t i = 0; i < n; ++i)
            labels[base + i] = std::uint8_t(in[i].inBox & detail::testPacked<Width>(table + std::size_t(in[i].column) * Width,
                                                                                   sprite, in[i].column, in[i].depth, rule));
    };
    if (begin >= end) return;
    locateBatch(begin, at[0]);
    int current = 0;
    for (std::size_t base = begin; base < end; base += kBatch) {
        if (base + kBatch < end) locateBatch(base + kBatch, at[1 - current]);
        answerBatch(base, at[current]);
        current = 1 - current;
    }
}

template <class Locate>
void classifyPacked(const Sprite& sprite, const detail::PackedTable& table, const Locate& where, const char* xyz,
                    std::size_t strideBytes, std::uint8_t* labels, Rule rule, std::size_t begin, std::size_t end) {
    if (table.width() == 8)
        classifyPacked<8>(sprite, table.records(), where, xyz, strideBytes, labels, rule, begin, end);
    else
        classifyPacked<4>(sprite, table.records(), where, xyz, strideBytes, labels, rule, begin, end);
}

} // namespace

namespace {
// A sprite the caller owns, as a Classifier for one call: the contract's
// checks and float64 points come from the base class.
class SpriteView final : public Classifier {
public:
    SpriteView(const Sprite& sprite, const SpriteQueryOptions& query) : sprite_(sprite), query_(query) {}
    Method method() const override { return Method::Sprite; }
    std::size_t memoryBytes() const override { return sprite_.memoryBytes(); }

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override {
        detail::classifySpriteFloats(sprite_, caps_, query_, xyz, count, strideBytes, labels, options);
    }

private:
    const Sprite& sprite_;
    SpriteQueryOptions query_;
    detail::BoundaryCapsCache caps_; // this call's
};
} // namespace

void classify(const Sprite& sprite, const PointsView& points, std::uint8_t* labels, const ClassifyOptions& options,
              const SpriteQueryOptions& query) {
    SpriteView(sprite, query).classify(points, labels, options);
}

SpriteClassifier::SpriteClassifier(Sprite sprite, const SpriteQueryOptions& query)
    : sprite_(std::move(sprite)), query_(query), caps_(std::make_unique<Caps>()) {}

SpriteClassifier::SpriteClassifier(const SpriteClassifier& other)
    : Classifier(other), sprite_(other.sprite_), query_(other.query_), caps_(std::make_unique<Caps>()) {}

SpriteClassifier::SpriteClassifier(SpriteClassifier&& other) noexcept = default;

SpriteClassifier& SpriteClassifier::operator=(const SpriteClassifier& other) {
    if (this != &other) {
        Classifier::operator=(other);
        sprite_ = other.sprite_;
        query_ = other.query_;
        caps_ = std::make_unique<Caps>();
    }
    return *this;
}

SpriteClassifier& SpriteClassifier::operator=(SpriteClassifier&& other) noexcept = default;

SpriteClassifier::~SpriteClassifier() = default;

std::size_t SpriteClassifier::memoryBytes() const {
    return sprite_.memoryBytes() + sprite_.boundaryEdges.size() * sizeof(glm::vec3);
}

std::string SpriteClassifier::summary() const {
    return "sprite " + std::to_string(sprite_.width()) + " x " + std::to_string(sprite_.height()) + " x " +
           std::to_string(sprite_.depthComplexity) + " along " + toString(sprite_.grid.axis);
}

void SpriteClassifier::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes,
                                      std::uint8_t* labels, const ClassifyOptions& options) const {
    const detail::BoundaryCapsCache callCaps; // a moved-from classifier's: this call's alone
    detail::classifySpriteFloats(sprite_, *(caps_ ? &caps_->cache : &callCaps), query_, xyz, count, strideBytes, labels,
                                 options);
}

namespace {

// The batch by the packed column table: the located points' records
// prefetched a batch ahead, by the sprite's own fast placement if it has one.
void classifyByTable(const Sprite& sprite, const detail::PackedTable& table, const char* xyz, std::size_t count,
                     std::size_t strideBytes, std::uint8_t* labels, const ClassifyOptions& options) {
    const SpriteGrid& grid = sprite.grid;
    AxisAligned<Axis::Z> z;
    AxisAligned<Axis::X> x;
    AxisAligned<Axis::Y> y;
    const int aligned = AxisAligned<Axis::Z>::applies(grid, z)   ? 1
                        : AxisAligned<Axis::X>::applies(grid, x) ? 2
                        : AxisAligned<Axis::Y>::applies(grid, y) ? 3
                                                                 : 0;
    detail::parallelFor(options.threads, count, std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
        const auto run = [&](const auto& where) {
            classifyPacked(sprite, table, where, xyz, strideBytes, labels, options.rule, begin, end);
        };
        switch (aligned) {
        case 1: run(z); break;
        case 2: run(x); break;
        case 3: run(y); break;
        default: run(General{});
        }
    });
}

// The batch by the sprite's own arrays: each point's offsets, then its
// crossings, both prefetched a batch at a time.
void classifyByOffsets(const Sprite& sprite, const char* xyz, std::size_t count, std::size_t strideBytes,
                       std::uint8_t* labels, const ClassifyOptions& options) {
    const SpriteGrid& grid = sprite.grid;
    detail::parallelFor(options.threads, count, std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
        constexpr std::size_t kBatch = 32;
        const std::uint32_t* offsets = sprite.offsets.data();
        const float* crossings = sprite.crossings.data();
        std::ptrdiff_t column[kBatch];
        float depth[kBatch];
        std::uint32_t first[kBatch], last[kBatch];
        for (std::size_t base = begin; base < end; base += kBatch) {
            const std::size_t n = std::min(kBatch, end - base);
            for (std::size_t i = 0; i < n; ++i) { // texel column and depth, the offsets prefetched
                glm::vec3 p;
                std::memcpy(&p, xyz + (base + i) * strideBytes, sizeof p);
                const glm::vec3 t = grid.toTexture(p);
                column[i] = detail::columnOf(grid, t);
                depth[i] = t.z;
                if (column[i] >= 0) __builtin_prefetch(offsets + column[i]);
            }
            for (std::size_t i = 0; i < n; ++i) {
                if (column[i] < 0) continue;
                first[i] = offsets[column[i]];
                last[i] = offsets[column[i] + 1];
                __builtin_prefetch(crossings + first[i]);
            }
            for (std::size_t i = 0; i < n; ++i)
                labels[base + i] =
                    column[i] >= 0 &&
                            detail::testColumn(crossings + first[i], crossings + last[i], depth[i], options.rule)
                        ? 1
                        : 0;
        }
    });
}

} // namespace

void detail::classifySpriteFloats(const Sprite& sprite, const BoundaryCapsCache& caps, const SpriteQueryOptions& query,
                                  const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                                  const ClassifyOptions& options) {
    detail::requireBoundaryKnown(sprite, options.rule);
    if (detail::needsBoundaryTerm(sprite, options.rule)) {
        const BoundaryCaps* built =
            query.boundary == BoundaryEvaluation::Caps ? &caps.get(sprite, options.threads) : nullptr;
        return detail::classifyGeneralizedWinding(sprite, built, xyz, count, strideBytes, labels, options);
    }
    assert(strideBytes >= 3 * sizeof(float) && ((xyz && labels) || count == 0));
    const char* points = reinterpret_cast<const char*>(xyz);
    const std::size_t columns = sprite.offsets.empty() ? 0 : sprite.offsets.size() - 1;
    // QueryLayout (see <vds/sprite.h>): with the column table each point
    // misses the cache once, on its column's record, which holds the first
    // four crossings (most columns have at most four), and is answered
    // without a branch on its data; a point behind the third crossing of a
    // deeper column reads it from the sprite. Otherwise each point reads its
    // offsets, then its crossings: two dependent misses, prefetched in
    // batches, and a loop over the crossings.
    const bool packed = query.layout == QueryLayout::Packed ||
                        (query.layout == QueryLayout::Auto && 2 * count >= columns);
    std::unique_ptr<const detail::PackedTable> table;
    if (packed && columns > 0) {
        try {
            table = std::make_unique<const detail::PackedTable>(sprite, options.threads);
        } catch (const std::bad_alloc&) {
            // No room for the table: the sprite's own arrays give the same answers.
        }
    }
    if (table) classifyByTable(sprite, *table, points, count, strideBytes, labels, options);
    else classifyByOffsets(sprite, points, count, strideBytes, labels, options);
}

SolidStatus solidStatus(const MeshReport& report) {
    return report.closed() && !report.misoriented() ? SolidStatus::Closed : SolidStatus::Open;
}

const char* statusWord(SolidStatus status, const std::string& validation) {
    if (status == SolidStatus::Closed) return "closed";
    return validation.rfind("closed", 0) == 0 ? "mis-oriented" : "open";
}


} // namespace vds
