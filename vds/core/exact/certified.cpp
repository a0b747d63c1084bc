// vds: certified classification (see <vds/certified.h> for the argument).
// The bands bound, per texel footprint, where the surface can be in depth;
// between them the answer is the one the exact classifier gives at the
// texel centre, found with its predicates and tie rule (projected_mesh.h).
#include <vds/certified.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

#include <vds/error.h>
#include <vds/mesh_check.h>
#include <vds/detail/parallel.h>

#include <vds/detail/projected_mesh.h>
#include <vds/detail/vpt.h>

namespace vds {
namespace {

// The widening of each footprint, in texels: far more than the float
// rounding of the texel lookup (a few ulps of at most 16384).
constexpr double kFootprintMargin = 1.0 / 64.0;

float roundDown(double x) {
    float f = float(x);
    if (double(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return std::nextafter(f, -std::numeric_limits<float>::infinity()); // and one ulp more, for the double rounding
}

float roundUp(double x) {
    float f = float(x);
    if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return std::nextafter(f, std::numeric_limits<float>::infinity());
}

struct Interval {
    float lo, hi;
    std::uint32_t triangle; // index in the mesh
};

// One triangle in view space (s, t, r) as doubles, with what the bands need.
struct ViewTriangle {
    double v[3][3];
    double sMin, sMax, tMin, tMax, rMin, rMax;
    // Plane r = a + b s + c t, when the triangle is not parallel to the axis.
    bool hasPlane;
    double a, b, c;
};

ViewTriangle viewTriangle(MeshView mesh, std::size_t k, const glm::ivec3& perm) {
    ViewTriangle t{};
    for (int corner = 0; corner < 3; ++corner)
        for (int axis = 0; axis < 3; ++axis) t.v[corner][axis] = mesh.positions[mesh.triangles[k][corner]][perm[axis]];
    t.sMin = std::min({t.v[0][0], t.v[1][0], t.v[2][0]});
    t.sMax = std::max({t.v[0][0], t.v[1][0], t.v[2][0]});
    t.tMin = std::min({t.v[0][1], t.v[1][1], t.v[2][1]});
    t.tMax = std::max({t.v[0][1], t.v[1][1], t.v[2][1]});
    t.rMin = std::min({t.v[0][2], t.v[1][2], t.v[2][2]});
    t.rMax = std::max({t.v[0][2], t.v[1][2], t.v[2][2]});
    const double e1s = t.v[1][0] - t.v[0][0], e1t = t.v[1][1] - t.v[0][1], e1r = t.v[1][2] - t.v[0][2];
    const double e2s = t.v[2][0] - t.v[0][0], e2t = t.v[2][1] - t.v[0][1], e2r = t.v[2][2] - t.v[0][2];
    const double ns = e1t * e2r - e1r * e2t, nt = e1r * e2s - e1s * e2r, nr = e1s * e2t - e1t * e2s;
    // Nearly vertical triangles get no plane: their own depth range bounds them.
    t.hasPlane = std::fabs(nr) > 1e-9 * (std::fabs(ns) + std::fabs(nt) + std::fabs(nr));
    if (t.hasPlane) {
        t.b = -ns / nr;
        t.c = -nt / nr;
        t.a = t.v[0][2] - t.b * t.v[0][0] - t.c * t.v[0][1];
    }
    return t;
}

// Whether the triangle's projection meets the rectangle [s0,s1] x [t0,t1]:
// boxes overlap and no edge of the triangle separates the rectangle from it.
bool overlaps(const ViewTriangle& t, double s0, double s1, double t0, double t1) {
    if (t.sMax < s0 || t.sMin > s1 || t.tMax < t0 || t.tMin > t1) return false;
    // Orientation of the projection, so that "outside" has one sign.
    const double area = (t.v[1][0] - t.v[0][0]) * (t.v[2][1] - t.v[0][1]) -
                        (t.v[1][1] - t.v[0][1]) * (t.v[2][0] - t.v[0][0]);
    if (area == 0.0) return true; // a segment or point in projection: the boxes decide
    const double sign = area > 0.0 ? 1.0 : -1.0;
    const double cs[4] = {s0, s1, s0, s1}, ct[4] = {t0, t0, t1, t1};
    for (int e = 0; e < 3; ++e) {
        const double* p = t.v[e];
        const double* q = t.v[(e + 1) % 3];
        bool allOutside = true;
        for (int k = 0; k < 4 && allOutside; ++k) {
            const double side = (q[0] - p[0]) * (ct[k] - p[1]) - (q[1] - p[1]) * (cs[k] - p[0]);
            allOutside = sign * side < 0.0;
        }
        if (allOutside) return false;
    }
    return true;
}

} // namespace

struct CertifiedClassifier::Impl {
    ExactClassifier exact;
    SpriteGrid grid;
    glm::ivec3 perm{0, 1, 2};
    bool certifies = false, certifiesWinding = false;
    Box box;
    // A band of a column: where the surface may be, in mesh units along the
    // axis, and the winding number of the gap above it (the gap below a
    // column's first band has winding 0: nothing is in front there).
    using Band = CertifiedBand;
    std::vector<std::uint32_t> offsets; // bands of column c: [offsets[c], offsets[c+1])
    std::vector<Band> bands;

    Impl(MeshView mesh, const CertifiedOptions& options) : exact(mesh, options.axis) {
        const MeshReport report = validateMesh(mesh);
        grid = makeGrid(report.bounds, options.axis, options.resolution);
        perm = axisPermutation(options.axis);
        box = report.bounds;
        // The gaps' argument needs the surface to be a cycle: mod 2 for the
        // parity rule (closed), with orientation for the winding numbers.
        certifies = report.closed();
        certifiesWinding = report.oriented();
        if (certifies) build(mesh, options.threads);
    }

    // The build, a row of texels at a time: each column's bands (the
    // merged depth ranges of the triangles whose footprint meets it) with
    // the winding number above each, counted at the texel's centre.
    void build(MeshView mesh, unsigned threads);
    struct Footprints {
        double originS = 0.0, originT = 0.0, texelS = 0.0, texelT = 0.0; ///< texel edges, mesh units
        std::uint32_t width = 0, height = 0;
    };
    struct TrianglesByRow {
        std::vector<ViewTriangle> tris;
        std::vector<std::uint32_t> start, of; ///< the triangles of row j: of[start[j] .. start[j+1])
    };
    struct ColumnScratch {
        std::vector<std::int32_t> bandOf, delta;
    };
    Footprints footprints() const;
    TrianglesByRow trianglesByRow(MeshView mesh, const Footprints& f) const;
    /// The depth intervals the row's triangles cover in each of its columns.
    void rowIntervals(const Footprints& f, const TrianglesByRow& rows, std::uint32_t j,
                      std::vector<std::vector<Interval>>& columns) const;
    /// Column (i, j)'s intervals merged into bands, appended to `outBands`; returns how many.
    std::uint32_t columnBands(const detail::ProjectedMesh& projected, std::vector<Interval>& list, std::uint32_t i,
                              std::uint32_t j, ColumnScratch& scratch, std::vector<Band>& outBands) const;
    void join(std::vector<std::vector<Band>>& rowBands, const std::vector<std::vector<std::uint32_t>>& rowCounts);

    // Where p's answer comes from: kOutside (certainly outside, no surface
    // out there), kExact (the exact path), or the column whose bands decide.
    static constexpr std::ptrdiff_t kOutside = -1, kExact = -2;
    std::ptrdiff_t locate(const glm::vec3& p, Rule rule) const {
        if (!certifies || (rule != Rule::Parity && !certifiesWinding)) return kExact;
        bool outside = false, onBoundary = false;
        for (int a = 0; a < 3; ++a) {
            if (!(p[a] >= box.lo[a] && p[a] <= box.hi[a])) outside = true;
            else if (p[a] == box.lo[a] || p[a] == box.hi[a]) onBoundary = true;
        }
        if (outside) return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) ? kOutside : kExact;
        if (onBoundary) return kExact;
        const std::ptrdiff_t column = detail::columnOf(grid, grid.toTexture(p));
        return column < 0 ? kExact : column;
    }

    // The winding of the gap holding depth z among bands [first, last), or
    // false when z lies in a band.
    bool gapWinding(const Band* first, const Band* last, float z, int& winding) const {
        winding = 0;
        for (const Band* b = first; b != last; ++b) {
            if (z < b->lo) return true;
            if (z <= b->hi) return false;
            winding = b->windingAbove;
        }
        return true;
    }

    bool certain(const glm::vec3& p, Rule rule, int& winding) const {
        const std::ptrdiff_t column = locate(p, rule);
        winding = 0;
        if (column == kOutside) return true;
        if (column == kExact) return false;
        const std::size_t c = std::size_t(column);
        return gapWinding(bands.data() + offsets[c], bands.data() + offsets[c + 1], p[perm.z], winding);
    }
};

void CertifiedClassifier::Impl::build(MeshView mesh, unsigned threads) {
    const detail::ProjectedMesh projected(mesh, grid.axis);
    const Footprints f = footprints();
    const TrianglesByRow rows = trianglesByRow(mesh, f);
    // Each row's bands and windings, then joined.
    std::vector<std::vector<Band>> rowBands(f.height);
    std::vector<std::vector<std::uint32_t>> rowCounts(f.height);
    detail::parallelFor(threads, f.height, 1, [&](std::size_t jBegin, std::size_t jEnd) {
        std::vector<std::vector<Interval>> columns(f.width);
        ColumnScratch scratch;
        for (std::size_t j = jBegin; j < jEnd; ++j) {
            rowIntervals(f, rows, std::uint32_t(j), columns);
            rowCounts[j].assign(f.width, 0);
            for (std::uint32_t i = 0; i < f.width; ++i)
                rowCounts[j][i] = columnBands(projected, columns[i], i, std::uint32_t(j), scratch, rowBands[j]);
        }
    });
    join(rowBands, rowCounts);
}

CertifiedClassifier::Impl::Footprints CertifiedClassifier::Impl::footprints() const {
    // Footprint edges along s and t in mesh units, from the lookup's own
    // matrix: texel i covers s in [lo_s + i / (m_s width), lo_s + (i+1) / (m_s width)).
    Footprints f;
    f.width = grid.width;
    f.height = grid.height;
    f.originS = grid.position[perm.x];
    f.originT = grid.position[perm.y];
    f.texelS = 1.0 / (double(grid.matrix[perm.x][0]) * f.width);
    f.texelT = 1.0 / (double(grid.matrix[perm.y][1]) * f.height);
    return f;
}

CertifiedClassifier::Impl::TrianglesByRow CertifiedClassifier::Impl::trianglesByRow(MeshView mesh,
                                                                                     const Footprints& f) const {
    TrianglesByRow rows;
    const std::size_t n = mesh.triangleCount;
    rows.tris.resize(n);
    // Rows each triangle's widened box reaches, and the triangles of each row (CSR).
    rows.start.assign(std::size_t(f.height) + 1, 0);
    const auto rowRange = [&](const ViewTriangle& t, std::uint32_t& j0, std::uint32_t& j1) {
        const double lo = std::floor((t.tMin - f.originT) / f.texelT - kFootprintMargin);
        const double hi = std::floor((t.tMax - f.originT) / f.texelT + kFootprintMargin);
        j0 = std::uint32_t(std::clamp(lo, 0.0, double(f.height - 1)));
        j1 = std::uint32_t(std::clamp(hi, 0.0, double(f.height - 1)));
    };
    for (std::size_t k = 0; k < n; ++k) {
        rows.tris[k] = viewTriangle(mesh, k, perm);
        std::uint32_t j0, j1;
        rowRange(rows.tris[k], j0, j1);
        for (std::uint32_t j = j0; j <= j1; ++j) ++rows.start[j + 1];
    }
    std::partial_sum(rows.start.begin(), rows.start.end(), rows.start.begin());
    rows.of.resize(rows.start.back());
    std::vector<std::uint32_t> next(rows.start.begin(), rows.start.end() - 1);
    for (std::size_t k = 0; k < n; ++k) {
        std::uint32_t j0, j1;
        rowRange(rows.tris[k], j0, j1);
        for (std::uint32_t j = j0; j <= j1; ++j) rows.of[next[j]++] = std::uint32_t(k);
    }
    return rows;
}

void CertifiedClassifier::Impl::rowIntervals(const Footprints& f, const TrianglesByRow& rows, std::uint32_t j,
                                             std::vector<std::vector<Interval>>& columns) const {
    for (auto& c : columns) c.clear();
    const double t0 = f.originT + (double(j) - kFootprintMargin) * f.texelT;
    const double t1 = f.originT + (double(j) + 1.0 + kFootprintMargin) * f.texelT;
    for (std::uint32_t r = rows.start[j]; r < rows.start[j + 1]; ++r) {
        const ViewTriangle& t = rows.tris[rows.of[r]];
        const double i0 = std::floor((t.sMin - f.originS) / f.texelS - kFootprintMargin);
        const double i1 = std::floor((t.sMax - f.originS) / f.texelS + kFootprintMargin);
        for (auto i = std::uint32_t(std::clamp(i0, 0.0, double(f.width - 1)));
             i <= std::uint32_t(std::clamp(i1, 0.0, double(f.width - 1))); ++i) {
            const double s0 = f.originS + (double(i) - kFootprintMargin) * f.texelS;
            const double s1 = f.originS + (double(i) + 1.0 + kFootprintMargin) * f.texelS;
            if (!overlaps(t, s0, s1, t0, t1)) continue;
            double lo = t.rMin, hi = t.rMax;
            if (t.hasPlane) {
                const double r00 = t.a + t.b * s0 + t.c * t0, r10 = t.a + t.b * s1 + t.c * t0;
                const double r01 = t.a + t.b * s0 + t.c * t1, r11 = t.a + t.b * s1 + t.c * t1;
                lo = std::max(lo, std::min({r00, r10, r01, r11}));
                hi = std::min(hi, std::max({r00, r10, r01, r11}));
                if (lo > hi) lo = hi = 0.5 * (lo + hi); // rounding of a nearly flat plane
            }
            columns[i].push_back({roundDown(lo), roundUp(hi), rows.of[r]});
        }
    }
}

std::uint32_t CertifiedClassifier::Impl::columnBands(const detail::ProjectedMesh& projected,
                                                     std::vector<Interval>& list, std::uint32_t i, std::uint32_t j,
                                                     ColumnScratch& scratch, std::vector<Band>& outBands) const {
    std::sort(list.begin(), list.end(), [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
    // Merge into bands; remember each interval's band.
    std::vector<std::int32_t>& bandOf = scratch.bandOf;
    bandOf.assign(list.size(), 0);
    std::size_t bandCount = 0;
    const std::size_t bandBase = outBands.size();
    for (std::size_t k = 0; k < list.size(); ++k) {
        if (bandCount > 0 && list[k].lo <= outBands.back().hi) {
            outBands.back().hi = std::max(outBands.back().hi, list[k].hi);
        } else {
            outBands.push_back({list[k].lo, list[k].hi, 0});
            ++bandCount;
        }
        bandOf[k] = std::int32_t(bandCount - 1);
    }
    // The centre's exact crossings, each counted in its band.
    std::vector<std::int32_t>& delta = scratch.delta;
    delta.assign(bandCount + 1, 0);
    const glm::vec3 centre = grid.texelCentre(i, j, 0.0f);
    float q[3];
    projected.toViewSpace(centre, q);
    const detail::CellGrid::Found found = projected.grid.find(q);
    for (const detail::CellEntry* e = found.begin; e != found.end; ++e) {
        if (!detail::CellGrid::mayHold(*e, found.sub)) continue;
        const detail::Triangle& tri = projected.tris[e->triangle];
        if (!detail::claims(tri, q)) continue;
        const auto it =
            std::find_if(list.begin(), list.end(), [&](const Interval& x) { return x.triangle == tri.index; });
        if (it == list.end()) throw Error("certified bake: a claimed triangle missed its footprint");
        delta[std::size_t(bandOf[std::size_t(it - list.begin())])] += (tri.flags & detail::kEntering) ? 1 : -1;
    }
    std::int32_t winding = 0;
    for (std::size_t m = 0; m < bandCount; ++m) {
        winding += delta[m];
        outBands[bandBase + m].windingAbove = winding;
    }
    return std::uint32_t(bandCount);
}

void CertifiedClassifier::Impl::join(std::vector<std::vector<Band>>& rowBands,
                                     const std::vector<std::vector<std::uint32_t>>& rowCounts) {
    const std::uint32_t width = grid.width, height = grid.height;
    offsets.assign(std::size_t(width) * height + 1, 0);
    std::size_t totalBands = 0;
    for (std::uint32_t j = 0; j < height; ++j)
        for (std::uint32_t i = 0; i < width; ++i) {
            totalBands += rowCounts[j][i];
            if (totalBands > std::numeric_limits<std::uint32_t>::max())
                throw OutOfMemory("certified bake: more than 2^32 bands; lower the resolution");
            offsets[std::size_t(j) * width + i + 1] = std::uint32_t(totalBands);
        }
    bands.reserve(totalBands);
    for (std::uint32_t j = 0; j < height; ++j) {
        bands.insert(bands.end(), rowBands[j].begin(), rowBands[j].end());
        std::vector<Band>().swap(rowBands[j]);
    }
}

CertifiedClassifier::CertifiedClassifier(MeshView mesh, const CertifiedOptions& options)
    : impl_(std::make_unique<Impl>(mesh, options)) {}
CertifiedClassifier::~CertifiedClassifier() = default;
CertifiedClassifier::CertifiedClassifier(CertifiedClassifier&&) noexcept = default;
CertifiedClassifier& CertifiedClassifier::operator=(CertifiedClassifier&&) noexcept = default;

bool CertifiedClassifier::contains(const glm::vec3& p, Rule rule) const {
    int winding = 0;
    if (impl_->certain(p, rule, winding)) return insideByRule(winding, rule);
    return impl_->exact.contains(p, rule);
}

void CertifiedClassifier::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes,
                                         std::uint8_t* labels, const ClassifyOptions& options) const {
    assert(strideBytes >= 3 * sizeof(float) && ((xyz && labels) || count == 0));
    const char* base = reinterpret_cast<const char*>(xyz);
    const Impl& impl = *impl_;
    std::atomic<std::size_t> exactCount{0};
    // As the sprite's batches: locate a batch of points and prefetch their
    // offsets, then their bands, then decide; misses overlap.
    detail::parallelFor(options.threads, count, std::size_t(1) << 14, [&](std::size_t begin, std::size_t end) {
        constexpr std::size_t kBatch = 32;
        std::ptrdiff_t where[kBatch];
        float depth[kBatch];
        std::uint32_t first[kBatch], last[kBatch];
        std::size_t local = 0;
        for (std::size_t b0 = begin; b0 < end; b0 += kBatch) {
            const std::size_t n = std::min(kBatch, end - b0);
            for (std::size_t i = 0; i < n; ++i) {
                glm::vec3 p;
                std::memcpy(&p, base + (b0 + i) * strideBytes, sizeof p);
                where[i] = impl.locate(p, options.rule);
                depth[i] = p[impl.perm.z];
                if (where[i] >= 0) __builtin_prefetch(impl.offsets.data() + where[i]);
            }
            for (std::size_t i = 0; i < n; ++i) {
                if (where[i] < 0) continue;
                first[i] = impl.offsets[std::size_t(where[i])];
                last[i] = impl.offsets[std::size_t(where[i]) + 1];
                __builtin_prefetch(impl.bands.data() + first[i]);
            }
            for (std::size_t i = 0; i < n; ++i) {
                int winding = 0;
                bool known = where[i] == Impl::kOutside;
                if (where[i] >= 0)
                    known = impl.gapWinding(impl.bands.data() + first[i], impl.bands.data() + last[i], depth[i], winding);
                if (!known) {
                    glm::vec3 p;
                    std::memcpy(&p, base + (b0 + i) * strideBytes, sizeof p);
                    labels[b0 + i] = impl.exact.contains(p, options.rule) ? 1 : 0;
                    ++local;
                    continue;
                }
                labels[b0 + i] = insideByRule(winding, options.rule) ? 1 : 0;
            }
        }
        exactCount += local;
    });
    if (options.stats) *options.stats = {count - exactCount.load(), exactCount.load()};
}

bool CertifiedClassifier::certifies() const { return impl_->certifies; }
const SpriteGrid& CertifiedClassifier::grid() const { return impl_->grid; }
const ExactClassifier& CertifiedClassifier::exact() const { return impl_->exact; }

std::size_t CertifiedClassifier::memoryBytes() const { return bandBytes() + impl_->exact.memoryBytes(); }

std::string CertifiedClassifier::summary() const {
    return "certified bands " + std::to_string(impl_->grid.width) + " x " + std::to_string(impl_->grid.height) +
           " along " + toString(impl_->grid.axis) + (impl_->certifies ? "" : " (mesh bounds no solid: all exact)");
}

CertifiedBands CertifiedClassifier::bands() const {
    const Impl& impl = *impl_;
    CertifiedBands b;
    b.box = impl.box;
    b.depthAxis = impl.perm.z;
    if (!impl.certifies) return b;
    b.offsets = impl.offsets.data();
    b.columnCount = impl.offsets.size() - 1;
    b.bands = impl.bands.data();
    b.bandCount = impl.bands.size();
    for (Rule rule : {Rule::Parity, Rule::Winding, Rule::GeneralizedWinding})
        if (rule == Rule::Parity || impl.certifiesWinding) b.certifiedRules |= std::uint8_t(1u << unsigned(rule));
    return b;
}

std::size_t CertifiedClassifier::bandBytes() const {
    return impl_->offsets.size() * sizeof(std::uint32_t) + impl_->bands.size() * sizeof(Impl::Band);
}

} // namespace vds
