// vds: the generalized winding number of a sprite (the Antipodal split,
// Martens, Trettner & Bessmeltsev, SIGGRAPH 2026): the integer term counted
// in the sprite's columns, the boundary term by the boundary's caps
// (winding/boundary_caps.h) or the per-edge sum (winding/antipodal.h).
#include <vds/detail/sprite_winding.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include <vds/error.h>
#include <vds/detail/parallel.h>

#include <vds/detail/vpt.h>
#include <vds/detail/antipodal.h>
#include <vds/detail/boundary_caps.h>

namespace vds::detail {

// ---------------------------------------------------------------- sprites

namespace {

/// Where a GWN query on a sprite takes its two terms, the grid's constants
/// taken once (the batch asks it of every point). The generalized winding
/// number of an open mesh need not vanish outside the sprite's box (just
/// beyond a large opening it exceeds 1/2), so queries are answered
/// everywhere. Within the texture across the axis, in front of or behind
/// the box too, the texel's column counts (none or all of its crossings in
/// front there) and B is taken at the texel's centre at the point's depth
/// (`SpriteGrid::texelCentre`, rounded as the CPU baker's ray is); beside
/// the texture the count is 0 (no ray there meets the mesh) and B is taken
/// at the point itself.
struct ColumnPoints {
    explicit ColumnPoints(const SpriteGrid& grid)
        : p(axisPermutation(grid.axis)), lo(grid.box.lo), width(float(grid.width)), height(float(grid.height)),
          depth(grid.box.hi[p.z] - grid.box.lo[p.z]), texel(grid.texelSize), columns(std::ptrdiff_t(grid.width)) {}
    /// Texture point `t` -> its column (-1 beside the texture) and the
    /// point B is taken at (mesh coordinates); reads no memory. False for
    /// a point that is not finite.
    bool place(const glm::vec3& t, std::ptrdiff_t& column, glm::vec3& q) const {
        if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z))) return false;
        // Without branches (whether a point lies within the texture is a
        // coin toss for points around the mesh) and without std::floor
        // (a dozen instructions each without SSE4.1): within the texture
        // the texel index is the truncation, clamped first so that the
        // conversion is defined for any finite point.
        const float xs = t.x * width, ys = t.y * height;
        const bool in = (xs >= 0.0f) & (xs < width) & (ys >= 0.0f) & (ys < height);
        const std::ptrdiff_t s = std::ptrdiff_t(std::fmin(std::fmax(xs, 0.0f), width));
        const std::ptrdiff_t r = std::ptrdiff_t(std::fmin(std::fmax(ys, 0.0f), height));
        column = (r * columns + s) | (std::ptrdiff_t(in) - 1); // -1 beside
        q[p.z] = lo[p.z] + t.z * depth;
        q[p.x] = lo[p.x] + pick(in, float(s) + 0.5f, xs) * texel;
        q[p.y] = lo[p.y] + pick(in, float(r) + 0.5f, ys) * texel;
        return true;
    }
    /// `in ? a : b` by bits, so that the compiler keeps it free of branches.
    static float pick(bool in, float a, float b) {
        std::uint32_t ua, ub;
        std::memcpy(&ua, &a, sizeof ua);
        std::memcpy(&ub, &b, sizeof ub);
        const std::uint32_t mask = 0u - std::uint32_t(in), bits = (ua & mask) | (ub & ~mask);
        float picked;
        std::memcpy(&picked, &bits, sizeof picked);
        return picked;
    }
    glm::ivec3 p;
    glm::vec3 lo;
    float width, height, depth, texel;
    std::ptrdiff_t columns;
};

/// The integer term of a placed point (ColumnPoints::place).
int columnCount(const Sprite& sprite, const glm::vec3& t, std::ptrdiff_t column) {
    return column >= 0 ? columnWinding(sprite.crossings.data() + sprite.offsets[std::size_t(column)],
                                       sprite.crossings.data() + sprite.offsets[std::size_t(column) + 1], t.z)
                       : 0;
}

/// Both terms' inputs at texture point `t`: false for a point that is not
/// finite.
bool gwnSample(const Sprite& sprite, const glm::vec3& t, int& winding, glm::vec3& point) {
    std::ptrdiff_t column;
    if (!ColumnPoints(sprite.grid).place(t, column, point)) return false;
    winding = columnCount(sprite, t, column);
    return true;
}

/// A sprite's columns as CellWindings for its caps' grid of bounds. A
/// query in a cell has its integer term counted in one column (the one
/// whose texel centre its point was moved to, gwnSample) at its depth, or
/// is 0 beside the texture. So where every column whose centre may lie in
/// the cell (a texel's margin all round) has no crossing within the cell's
/// depths (a margin for the rounding of depth to float), each counts the
/// same in front at every depth of the cell; where they all count alike,
/// and beside the texture (if the cell reaches past it) that is 0, the
/// integer term is that one count over the cell. In the boundary's sweep
/// the columns count apart (across the sweep a crossing ends at the
/// boundary), but the caps' crossings of the same columns at the point B
/// is taken at make up the difference: where neither the mesh's crossings
/// nor the caps' lie within the cell's depths and every column's sum is
/// alike, the closed count is that sum, for the queries placed in a
/// column: those beside the texture in such a cell ask insideApart (their
/// count is 0 and B is taken at the point itself, which no column's sum
/// speaks of). Reads the sprite during constantWindings() only.
class SpriteColumns final : public CellWindings {
public:
    /// `threads`: over the cells' columns along the axis (0: all cores).
    SpriteColumns(const Sprite& sprite, unsigned threads) : sprite_(sprite), threads_(threads) {}
    void constantWindings(const CellLattice& cells, const ProjectedMesh* caps, std::vector<std::int32_t>& windings,
                          std::vector<std::int32_t>& closed) const override;

private:
    const Sprite& sprite_;
    unsigned threads_;
};

/// A column's counts, layer by layer, four bits a layer (the count plus 8)
/// in two words (layers 0-15, 16-31): a crossing adds its sign to every
/// layer after the ones it may lie in, so that comparing columns is an
/// exclusive or. Counts beyond +-7 do not fit: such a footprint vouches
/// for no layer.
struct Nibbles {
    std::uint64_t low = 0, high = 0;
    Nibbles operator^(const Nibbles& o) const { return {low ^ o.low, high ^ o.high}; }
    Nibbles& operator|=(const Nibbles& o) {
        low |= o.low;
        high |= o.high;
        return *this;
    }
    unsigned at(std::uint32_t k) const { return unsigned(((k < 16 ? low >> (4 * k) : high >> (4 * (k - 16)))) & 0xfu); }
    /// Every nibble of `ones` (each 0 or 1) made 0xf.
    static Nibbles spread(const Nibbles& ones) { return {ones.low * 0xfu, ones.high * 0xfu}; }
};

/// The cells' layers along the sprite's axis in texture depth. Layer k
/// spans [first + k step, first + (k + 1) step] widened by `margin` each
/// way, for the rounding of a point's depth and of its position from it
/// (float, some 1e-7 of the coordinates' magnitude), generously. A
/// crossing at depth d lies in the widened layers from
/// floor((d - first - 2 margin) / step) to floor((d - first + 2 margin) /
/// step) at most (twice the margin: room for the rounding of these
/// quotients, taken by the reciprocal); a layer holding none of a column's
/// crossings has the column's count at every depth in it, and the
/// crossings before it counted.
struct Layers {
    static constexpr std::uint32_t kMost = 32; // four bits a layer in two words
    /// Whether the grid's layers and the sprite's depth allow them.
    static bool fit(const SpriteGrid& g, const CellLattice& cells, const glm::ivec3& p) {
        const std::uint32_t layers = cells.dims[p.z];
        if (layers == 0 || layers > kMost || !(g.texelSize > 0.0f)) return false;
        const double depth = double(g.box.hi[p.z]) - g.box.lo[p.z];
        return depth > 0.0 && cells.size[p.z] > 0.0;
    }
    Layers(const SpriteGrid& g, const CellLattice& cells, const glm::ivec3& p)
        : count(cells.dims[p.z]), boxLo(g.box.lo[p.z]), depth(double(g.box.hi[p.z]) - boxLo) {
        const double zLo = cells.lo[p.z], zHi = zLo + double(count) * cells.size[p.z];
        margin = 1e-6 * (std::fabs(zLo) + std::fabs(zHi) + std::fabs(boxLo) + std::fabs(double(g.box.hi[p.z])) + depth) /
                 depth;
        first = (zLo - boxLo) / depth;
        inverse = depth / cells.size[p.z];
        // Twice the margin in layers, and room for the rounding of x below.
        reach = 2.0 * margin * inverse + 1e-9;
        // after[t]: a 1 in the nibbles of layers t on.
        for (std::uint32_t t = 0; t <= count; ++t)
            for (std::uint32_t k = t; k < count; ++k) (k < 16 ? after[t].low : after[t].high) |= std::uint64_t(1) << (4 * (k % 16));
        for (std::uint32_t k = 0; k < count; ++k) (k < 16 ? zero.low : zero.high) |= std::uint64_t(8) << (4 * (k % 16));
    }
    /// floor((d - first) / step) in [-1, count].
    std::int64_t of(double d) const {
        const double x = (d - first) * inverse;
        if (!(x >= 0.0)) return -1;
        if (x >= double(count)) return std::int64_t(count);
        return std::int64_t(x);
    }
    /// Counts of one column's crossings [c, last) into `counts`; layers a
    /// crossing may lie in into `spoilt` (a nibble 0xf each); false where
    /// a count does not fit.
    bool column(const float* c, const float* last, Nibbles& counts, Nibbles& spoilt, int& peak) const;

    std::uint32_t count;
    double boxLo, depth, margin, first, inverse, reach;
    Nibbles after[kMost + 1];
    Nibbles zero; ///< every layer counting 0
};

bool Layers::column(const float* c, const float* last, Nibbles& counts, Nibbles& spoilt, int& peak) const {
    counts = zero;
    int running = 0;
    peak = 0;
    for (; c != last; ++c) {
        const double d = std::fabs(double(*c));
        const double x = (d - first) * inverse;
        std::int64_t from, to;
        if (x >= 0.0 && x < double(count)) {
            const std::int64_t k = std::int64_t(x);
            const double fraction = x - double(k);
            from = k - (fraction < reach ? 1 : 0);
            to = k + (fraction > 1.0 - reach ? 1 : 0);
        } else if (x < 0.0 || x >= double(count)) {
            from = of(d - 2.0 * margin);
            to = of(d + 2.0 * margin);
        } else {
            return false; // not a number: columnWinding stops there
        }
        from = std::max<std::int64_t>(from, 0);
        const std::int64_t next = std::min<std::int64_t>(to + 1, count); // counts it from here on
        if (from < next) spoilt |= Nibbles::spread(after[from] ^ after[next]);
        const bool enters = crossingEnters(*c);
        running += enters ? 1 : -1;
        if (running > 7 || running < -7) return false;
        peak = std::max(peak, std::abs(running));
        if (next >= std::int64_t(count)) break; // it and the rest lie behind every layer
        if (enters) {
            counts.low += after[next].low;
            counts.high += after[next].high;
        } else {
            counts.low -= after[next].low;
            counts.high -= after[next].high;
        }
    }
    return true;
}

/// The caps' crossings of one column, as the query's count takes them
/// (ProjectedMesh::winding at the point B is taken at: the texel centre as
/// ColumnPoints places it, at the query's depth): a cap triangle that
/// claims the column counts at the depths past its farthest vertex, none
/// before its nearest; between, its layers are spoilt. The change to the
/// column's counts (`delta`, nibble by nibble; added to the counts in any
/// order it gives the same word), the layers spoilt, and the crossings
/// (for the fit: the column's peak count plus these within +-7).
struct CapColumn {
    Nibbles delta, spoilt;
    int crossings = 0;
};

/// Where the line t = rowT crosses triangle `tri` in (s, t), from its
/// edges' crossings of the line, in double: [left, right]; false where it
/// does not.
bool rowSpan(const Triangle& tri, float rowT, double& left, double& right) {
    left = std::numeric_limits<double>::infinity();
    right = -left;
    for (int e = 0; e < 3; ++e) {
        const float* a = tri.v[e];
        const float* b = tri.v[(e + 1) % 3];
        if ((a[1] < rowT && b[1] < rowT) || (a[1] > rowT && b[1] > rowT)) continue;
        if (a[1] == b[1]) { // along the line
            left = std::min({left, double(a[0]), double(b[0])});
            right = std::max({right, double(a[0]), double(b[0])});
            continue;
        }
        const double x = double(a[0]) + (double(rowT) - double(a[1])) / (double(b[1]) - double(a[1])) *
                                            (double(b[0]) - double(a[0]));
        left = std::min(left, x);
        right = std::max(right, x);
    }
    return left <= right;
}

/// One call of SpriteColumns::constantWindings: the footprints (columns
/// of cells along the axis) apart, each writing its own cells.
class ColumnWindingsPass {
public:
    ColumnWindingsPass(const Sprite& sprite, const CellLattice& cells, const ProjectedMesh* caps,
                       std::vector<std::int32_t>& windings, std::vector<std::int32_t>& closed)
        : sprite_(sprite), g_(sprite.grid), cells_(cells), caps_(caps), p_(axisPermutation(sprite.grid.axis)),
          layers_(sprite.grid, cells, p_), place_(sprite.grid), windings_(windings), closed_(closed) {
        if (caps) sweep();
    }
    std::size_t footprints() const { return std::size_t(cells_.dims[p_.x]) * cells_.dims[p_.y]; }
    void footprint(std::size_t f) const;

private:
    /// A footprint's counts so far, over its columns.
    struct Compared {
        // Per column: its counts, and with the caps' crossings added
        // (`capped`); layers a crossing of the mesh may lie in (`within`),
        // layers some column counts apart in (`apart`), the same with the
        // caps (`cappedWithin`, `cappedApart`).
        Nibbles reference, counts, within, apart;
        Nibbles cappedReference, capped, cappedWithin, cappedApart;
        bool counted = false, closes = false, empty = false;
    };
    /// The footprints, as (i, j) ranges, a box in (s, t) two texels wider
    /// each way overlaps; false for a box that is not finite.
    bool overlapped(const float* lo, const float* hi, std::int64_t (&range)[2][2]) const;
    /// The footprints some boundary edge's box (two texels wider each
    /// way) overlaps, swept_ (the boundary's sweep passes through no
    /// other: the caps' grid asks for the closed count in the sweep only),
    /// and the caps' triangles whose box overlaps each: capsIn_ from
    /// capsFirst_[f] to capsFirst_[f + 1].
    void sweep();
    /// The texels whose centres may lie in footprint (i, j) (a texel
    /// beyond it each way); `empty` where those run past the texture
    /// (some query there counts 0 at every depth). False where the
    /// footprint is not finite.
    bool texels(std::uint32_t i, std::uint32_t j, std::int64_t (&lowest)[2], std::int64_t (&highest)[2],
                bool& empty) const;
    /// The caps' crossings of footprint f's columns [lowest, highest].
    void capColumns(std::size_t f, const std::int64_t (&lowest)[2], const std::int64_t (&highest)[2],
                    std::vector<CapColumn>& out) const;
    /// Cap triangle `tri`'s crossings of the columns [lowest, highest]
    /// near it, into `out` (row by row, `across` a row).
    void addCapTriangle(const Triangle& tri, const std::int64_t (&lowest)[2], const std::int64_t (&highest)[2],
                        std::vector<CapColumn>& out) const;
    /// Every column of the footprint counted and compared; false where a
    /// count does not fit.
    bool compare(const std::int64_t (&lowest)[2], const std::int64_t (&highest)[2],
                 const std::vector<CapColumn>& capColumn, Compared& m) const;

    const Sprite& sprite_;
    const SpriteGrid& g_;
    const CellLattice& cells_;
    const ProjectedMesh* caps_;
    const glm::ivec3 p_;
    const Layers layers_;
    const ColumnPoints place_;
    std::vector<std::uint8_t> swept_;
    std::vector<std::uint32_t> capsFirst_, capsIn_;
    std::vector<std::int32_t>& windings_;
    std::vector<std::int32_t>& closed_;
};

bool ColumnWindingsPass::overlapped(const float* lo, const float* hi, std::int64_t (&range)[2][2]) const {
    for (int u = 0; u < 2; ++u) {
        const int axis = u == 0 ? p_.x : p_.y;
        const double from = std::floor((double(lo[u]) - 2.0 * double(g_.texelSize) - cells_.lo[axis]) / cells_.size[axis]);
        const double to = std::floor((double(hi[u]) + 2.0 * double(g_.texelSize) - cells_.lo[axis]) / cells_.size[axis]);
        if (!(from >= -1e18 && to <= 1e18)) return false; // not NaN, not absurd
        range[u][0] = std::int64_t(std::max(from, 0.0));
        range[u][1] = std::int64_t(std::min(to, double(cells_.dims[axis]) - 1.0));
    }
    return true;
}

void ColumnWindingsPass::sweep() {
    const std::size_t footprintCount = footprints();
    swept_.assign(footprintCount, 0);
    for (std::size_t e = 0; e + 1 < sprite_.boundaryEdges.size(); e += 2) {
        const glm::vec3 &a = sprite_.boundaryEdges[e], &b = sprite_.boundaryEdges[e + 1];
        const float lo[2] = {std::min(a[p_.x], b[p_.x]), std::min(a[p_.y], b[p_.y])};
        const float hi[2] = {std::max(a[p_.x], b[p_.x]), std::max(a[p_.y], b[p_.y])};
        std::int64_t range[2][2];
        if (!overlapped(lo, hi, range)) continue;
        for (std::int64_t j = range[1][0]; j <= range[1][1]; ++j)
            for (std::int64_t i = range[0][0]; i <= range[0][1]; ++i)
                swept_[std::size_t(j) * cells_.dims[p_.x] + std::size_t(i)] = 1;
    }
    capsFirst_.assign(footprintCount + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::uint32_t> next;
        if (pass == 1) {
            for (std::size_t f = 0; f < footprintCount; ++f) capsFirst_[f + 1] += capsFirst_[f];
            capsIn_.resize(capsFirst_[footprintCount]);
            next.assign(capsFirst_.begin(), capsFirst_.end() - 1);
        }
        for (std::size_t k = 0; k < caps_->crossable; ++k) {
            const Triangle& tri = caps_->tris[k];
            const float lo[2] = {std::min({tri.v[0][0], tri.v[1][0], tri.v[2][0]}), std::min({tri.v[0][1], tri.v[1][1], tri.v[2][1]})};
            const float hi[2] = {std::max({tri.v[0][0], tri.v[1][0], tri.v[2][0]}), std::max({tri.v[0][1], tri.v[1][1], tri.v[2][1]})};
            std::int64_t range[2][2];
            if (!overlapped(lo, hi, range)) continue;
            for (std::int64_t j = range[1][0]; j <= range[1][1]; ++j)
                for (std::int64_t i = range[0][0]; i <= range[0][1]; ++i) {
                    const std::size_t f = std::size_t(j) * cells_.dims[p_.x] + std::size_t(i);
                    if (!swept_[f]) continue;
                    if (pass == 0) ++capsFirst_[f + 1];
                    else capsIn_[next[f]++] = std::uint32_t(k);
                }
        }
    }
}

void ColumnWindingsPass::capColumns(std::size_t f, const std::int64_t (&lowest)[2], const std::int64_t (&highest)[2],
                                    std::vector<CapColumn>& out) const {
    const std::int64_t across = highest[0] - lowest[0] + 1;
    out.assign(std::size_t(across * (highest[1] - lowest[1] + 1)), CapColumn{});
    for (std::uint32_t c = capsFirst_[f]; c < capsFirst_[f + 1]; ++c) addCapTriangle(caps_->tris[capsIn_[c]], lowest, highest, out);
}

void ColumnWindingsPass::addCapTriangle(const Triangle& tri, const std::int64_t (&lowest)[2],
                                        const std::int64_t (&highest)[2], std::vector<CapColumn>& out) const {
    const std::int64_t across = highest[0] - lowest[0] + 1;
    const Layers& L = layers_;
    const double nearest = std::min({tri.v[0][2], tri.v[1][2], tri.v[2][2]});
    const double farthest = std::max({tri.v[0][2], tri.v[1][2], tri.v[2][2]});
    const std::int64_t from = std::max<std::int64_t>(L.of((nearest - L.boxLo) / L.depth - 2.0 * L.margin), 0);
    const std::int64_t next =
        std::min<std::int64_t>(L.of((farthest - L.boxLo) / L.depth + 2.0 * L.margin) + 1, L.count);
    Nibbles spoils;
    if (from < next) spoils = Nibbles::spread(L.after[from] ^ L.after[next]);
    const Nibbles step = next < std::int64_t(L.count) ? L.after[next] : Nibbles{};
    const bool enters = (tri.flags & kEntering) != 0;
    // The footprint's columns within the triangle's box.
    std::int64_t range[2][2];
    for (int u = 0; u < 2; ++u) {
        const float lo = std::min({tri.v[0][u], tri.v[1][u], tri.v[2][u]});
        const float hi = std::max({tri.v[0][u], tri.v[1][u], tri.v[2][u]});
        const int axis = u == 0 ? p_.x : p_.y;
        range[u][0] = std::max<std::int64_t>(lowest[u], std::int64_t(std::floor((double(lo) - double(place_.lo[axis])) / double(place_.texel))) - 1);
        range[u][1] = std::min<std::int64_t>(highest[u], std::int64_t(std::floor((double(hi) - double(place_.lo[axis])) / double(place_.texel))) + 1);
    }
    for (std::int64_t t = range[1][0]; t <= range[1][1]; ++t) {
        // The row's columns near the triangle: where its centre line meets
        // the triangle, a column more each way for the rounding; the claims
        // test decides.
        const float rowT = place_.lo[p_.y] + (float(t) + 0.5f) * place_.texel;
        double left, right;
        if (!rowSpan(tri, rowT, left, right)) continue;
        const std::int64_t s0 = std::max<std::int64_t>(
            range[0][0], std::int64_t(std::floor((left - double(place_.lo[p_.x])) / double(place_.texel) - 0.5)) - 1);
        const std::int64_t s1 = std::min<std::int64_t>(
            range[0][1], std::int64_t(std::floor((right - double(place_.lo[p_.x])) / double(place_.texel) - 0.5)) + 1);
        for (std::int64_t s = s0; s <= s1; ++s) {
            const float q[2] = {place_.lo[p_.x] + (float(s) + 0.5f) * place_.texel, rowT};
            if (!claims(tri, q)) continue;
            CapColumn& column = out[std::size_t((t - lowest[1]) * across + (s - lowest[0]))];
            ++column.crossings;
            column.spoilt |= spoils;
            if (enters) {
                column.delta.low += step.low;
                column.delta.high += step.high;
            } else {
                column.delta.low -= step.low;
                column.delta.high -= step.high;
            }
        }
    }
}

bool ColumnWindingsPass::texels(std::uint32_t i, std::uint32_t j, std::int64_t (&lowest)[2],
                                std::int64_t (&highest)[2], bool& empty) const {
    const std::uint32_t at[2] = {i, j};
    const std::uint32_t extent[2] = {g_.width, g_.height};
    const int axes[2] = {p_.x, p_.y};
    const double texel = g_.texelSize;
    bool fits = true;
    empty = false;
    for (int u = 0; u < 2; ++u) {
        const double lo = cells_.lo[axes[u]] + double(at[u]) * cells_.size[axes[u]];
        const double hi = lo + cells_.size[axes[u]];
        const double a = std::floor((lo - double(g_.box.lo[axes[u]])) / texel) - 1.0;
        const double b = std::floor((hi - double(g_.box.lo[axes[u]])) / texel) + 1.0;
        if (!(a >= -1e9 && b <= 1e9)) fits = false; // not finite, or absurd
        empty = empty || a < 0.0 || b >= double(extent[u]);
        lowest[u] = fits ? std::max<std::int64_t>(0, std::int64_t(a)) : 0;
        highest[u] = fits ? std::min<std::int64_t>(std::int64_t(extent[u]) - 1, std::int64_t(b)) : -1;
    }
    return fits;
}

bool ColumnWindingsPass::compare(const std::int64_t (&lowest)[2], const std::int64_t (&highest)[2],
                                 const std::vector<CapColumn>& capColumn, Compared& m) const {
    for (std::int64_t t = lowest[1]; t <= highest[1]; ++t)
        for (std::int64_t s = lowest[0]; s <= highest[0]; ++s) {
            const std::size_t column = std::size_t(t) * g_.width + std::size_t(s);
            const float* c = sprite_.crossings.data() + sprite_.offsets[column];
            const float* last = sprite_.crossings.data() + sprite_.offsets[column + 1];
            int peak = 0;
            if (c == last) {
                m.empty = true; // counts 0 at every depth: compared below
                if (!m.closes) continue;
                m.counts = layers_.zero;
            } else if (!layers_.column(c, last, m.counts, m.within, peak)) {
                return false;
            }
            if (m.closes) {
                const CapColumn& capsThere =
                    capColumn[std::size_t((t - lowest[1]) * (highest[0] - lowest[0] + 1) + (s - lowest[0]))];
                m.closes = peak + capsThere.crossings <= 7;
                m.capped = {m.counts.low + capsThere.delta.low, m.counts.high + capsThere.delta.high};
                m.cappedWithin |= capsThere.spoilt;
            }
            // The first column is the reference; the rest compare with it.
            if (m.counted) {
                m.apart |= m.counts ^ m.reference;
                m.cappedApart |= m.capped ^ m.cappedReference;
            } else {
                m.reference = m.counts;
                m.cappedReference = m.capped;
                m.counted = true;
            }
        }
    return true;
}

void ColumnWindingsPass::footprint(std::size_t f) const {
    const std::uint32_t i = std::uint32_t(f % cells_.dims[p_.x]), j = std::uint32_t(f / cells_.dims[p_.x]);
    std::int64_t lowest[2], highest[2];
    Compared m;
    if (!texels(i, j, lowest, highest, m.empty)) return;
    m.reference = m.cappedReference = layers_.zero;
    // Beside the texture too: the closed counts speak of the queries
    // placed in a column (a query beside it asks insideApart).
    m.closes = caps_ != nullptr && swept_[f] != 0 && lowest[0] <= highest[0] && lowest[1] <= highest[1];
    thread_local std::vector<CapColumn> capColumn;
    if (m.closes) capColumns(f, lowest, highest, capColumn);
    if (!compare(lowest, highest, capColumn, m)) return;
    // Where a column counts 0 everywhere, only 0 is shared (beside the
    // texture, the count is 0).
    if (m.empty) m.apart |= m.reference ^ layers_.zero;
    const Nibbles spoilt{m.within.low | m.apart.low, m.within.high | m.apart.high};
    for (std::uint32_t k = 0; k < layers_.count; ++k) {
        glm::uvec3 cell;
        cell[p_.x] = i;
        cell[p_.y] = j;
        cell[p_.z] = k;
        if (spoilt.at(k) == 0) windings_[cells_.index(cell)] = std::int32_t(m.reference.at(k)) - 8;
        // The closed count: no crossing of the mesh or the caps within the
        // layer, and every column's sum alike.
        if (m.closes && m.within.at(k) == 0 && m.cappedWithin.at(k) == 0 && m.cappedApart.at(k) == 0)
            closed_[cells_.index(cell)] = std::int32_t(m.cappedReference.at(k)) - 8;
    }
}

void SpriteColumns::constantWindings(const CellLattice& cells, const ProjectedMesh* caps,
                                     std::vector<std::int32_t>& windings, std::vector<std::int32_t>& closed) const {
    if (!Layers::fit(sprite_.grid, cells, axisPermutation(sprite_.grid.axis))) return;
    const ColumnWindingsPass pass(sprite_, cells, caps, windings, closed);
    detail::parallelFor(threads_, pass.footprints(), 8, [&](std::size_t begin, std::size_t end) {
        for (std::size_t f = begin; f < end; ++f) pass.footprint(f);
    });
}

} // namespace

void requireBoundaryKnown(const Sprite& sprite, Rule rule) {
    if (rule == Rule::GeneralizedWinding && sprite.status == SolidStatus::Open && !sprite.boundaryKnown)
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
}

namespace {

/// classifyGeneralizedWinding's points from one thread, in batches, three
/// in flight, so that each cache miss has a whole batch's work to arrive:
/// find batch k's points (no memory read), label those whose cell of the
/// caps answers alone and prefetch the rest's offsets; read batch k - 1's
/// offsets and prefetch their crossings; count batch k - 2's crossings and
/// label them.
class BatchedLabels {
public:
    static constexpr std::size_t kBatch = 32;
    BatchedLabels(const Sprite& sprite, const BoundaryCaps* caps, const ColumnPoints& place, const char* base,
                  std::size_t strideBytes, std::uint8_t* labels)
        : sprite_(sprite), caps_(caps), place_(place), base_(base), strideBytes_(strideBytes), labels_(labels),
          offsets_(sprite.offsets.data()), crossings_(sprite.crossings.data()),
          axis_(axisPermutation(sprite.grid.axis).z) {}

    void run(std::size_t begin, std::size_t end) {
        const std::size_t batches = (end - begin + kBatch - 1) / kBatch;
        for (std::size_t k = 0; k < batches + 2; ++k) {
            if (k < batches) place(ring_[k % 3], begin + k * kBatch, std::min(kBatch, end - (begin + k * kBatch)));
            if (k >= 1 && k - 1 < batches) readOffsets(ring_[(k - 1) % 3]);
            if (k >= 2) label(ring_[(k - 2) % 3]);
        }
    }

private:
    struct Pending {
        std::size_t index;         ///< of the point
        std::ptrdiff_t column;     ///< -1 beside the texture
        float depth;               ///< texture depth
        glm::vec3 point;           ///< where B is taken
        const float *first, *last; ///< the column's crossings (stage 2)
    };
    struct Batch {
        Pending pending[kBatch];
        std::size_t waiting = 0;
    };

    /// Stage 1: points [b0, b0 + n) placed, labelled where their cell
    /// answers alone, the rest's offsets prefetched.
    void place(Batch& batch, std::size_t b0, std::size_t n) {
        batch.waiting = 0;
        // Every point placed first, then every cell asked: two short loops
        // whose iterations overlap, where one long chain of dependent steps
        // a point did not.
        glm::vec3 q[kBatch];
        float depth[kBatch];
        std::ptrdiff_t column[kBatch];
        bool finite[kBatch];
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec3 p;
            std::memcpy(&p, base_ + (b0 + i) * strideBytes_, sizeof p);
            const glm::vec3 t = textureOf(sprite_.grid, p);
            finite[i] = place_.place(t, column[i], q[i]);
            depth[i] = t.z;
        }
        for (std::size_t i = 0; i < n; ++i) {
            if (!finite[i]) {
                labels_[b0 + i] = 0;
                continue;
            }
            const int alone = caps_ ? caps_->insideAlone(q[i], column[i] < 0) : -1;
            if (alone >= 0) {
                labels_[b0 + i] = std::uint8_t(alone);
                continue;
            }
            batch.pending[batch.waiting++] = {b0 + i, column[i], depth[i], q[i], nullptr, nullptr};
            if (column[i] >= 0) __builtin_prefetch(offsets_ + column[i]);
        }
    }

    /// Stage 2: the pending points' columns found, their crossings
    /// prefetched.
    void readOffsets(Batch& batch) const {
        for (std::size_t w = 0; w < batch.waiting; ++w) {
            Pending& at = batch.pending[w];
            if (at.column < 0) continue;
            at.first = crossings_ + offsets_[at.column];
            at.last = crossings_ + offsets_[at.column + 1];
            __builtin_prefetch(at.first);
        }
    }

    /// Stage 3: the pending points counted and labelled.
    void label(const Batch& batch) const {
        for (std::size_t w = 0; w < batch.waiting; ++w) {
            const Pending& at = batch.pending[w];
            const int winding = at.column >= 0 ? columnWinding(at.first, at.last, at.depth) : 0;
            labels_[at.index] =
                (caps_ ? (at.column >= 0 ? caps_->inside(winding, at.point) : caps_->insideApart(winding, at.point))
                       : generalizedWindingInside(double(winding) + boundaryTermExact(sprite_.boundaryEdges.data(),
                                                                                      sprite_.boundaryEdges.size() / 2,
                                                                                      axis_, glm::dvec3(at.point))))
                    ? 1
                    : 0;
        }
    }

    const Sprite& sprite_;
    const BoundaryCaps* caps_;
    const ColumnPoints& place_;
    const char* base_;
    std::size_t strideBytes_;
    std::uint8_t* labels_;
    const std::uint32_t* offsets_;
    const float* crossings_;
    int axis_;
    Batch ring_[3];
};

} // namespace

void classifyGeneralizedWinding(const Sprite& sprite, const BoundaryCaps* caps, const float* xyz, std::size_t count,
                                std::size_t strideBytes, std::uint8_t* labels, const ClassifyOptions& options) {
    const ColumnPoints place(sprite.grid);
    detail::parallelFor(options.threads, count, 1024, [&](std::size_t begin, std::size_t end) {
        BatchedLabels(sprite, caps, place, reinterpret_cast<const char*>(xyz), strideBytes, labels).run(begin, end);
    });
}

const BoundaryCaps& BoundaryCapsCache::get(const Sprite& sprite, unsigned threads) const {
    if (const BoundaryCaps* caps = caps_.load(std::memory_order_acquire)) return *caps;
    const SpriteColumns columns(sprite, threads);
    auto built = std::make_unique<BoundaryCaps>(sprite.boundaryEdges.data(), sprite.boundaryEdges.size() / 2,
                                                sprite.grid.axis, &sprite.grid.box, nullptr, &columns);
    const BoundaryCaps* expected = nullptr;
    if (caps_.compare_exchange_strong(expected, built.get(), std::memory_order_acq_rel)) return *built.release();
    return *expected; // another thread built it first
}

void BoundaryCapsCache::reset() noexcept { delete caps_.exchange(nullptr); }

bool containsGeneralizedWinding(const Sprite& sprite, const glm::vec3& world) {
    requireBoundaryKnown(sprite, Rule::GeneralizedWinding);
    std::uint8_t label = 0; // the batch's per-edge path, so that one point answers as a batch does
    classifyGeneralizedWinding(sprite, nullptr, &world.x, 1, sizeof world, &label, {Rule::GeneralizedWinding, 1});
    return label != 0;
}

} // namespace vds::detail

namespace vds {

double Sprite::generalizedWinding(const glm::vec3& world) const {
    detail::requireBoundaryKnown(*this, Rule::GeneralizedWinding);
    const glm::vec3 t = grid.toTexture(world);
    if (boundaryEdges.empty()) {
        const std::ptrdiff_t column = detail::columnOf(grid, t);
        if (column < 0) return 0.0;
        return double(detail::columnWinding(crossings.data() + offsets[std::size_t(column)],
                                            crossings.data() + offsets[std::size_t(column) + 1], t.z));
    }
    int winding = 0;
    glm::vec3 q;
    if (!detail::gwnSample(*this, t, winding, q))
        return 0.0;
    return double(winding) + detail::boundaryTermExact(boundaryEdges.data(), boundaryEdges.size() / 2,
                                                       axisPermutation(grid.axis).z, glm::dvec3(q));
}

} // namespace vds
