// vds: the boundary term of the Antipodal split of the generalized winding
// number (Martens, Trettner & Bessmeltsev, SIGGRAPH 2026, arXiv 2605.01536),
// for sprites, the exact classifier and the voxelizers; see boundary_term.h.
#include "boundary_term.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <tuple>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/parallel.h>

#include "sprite_lookup.h"

namespace vds::detail {

namespace {
constexpr double kFourPi = 4.0 * 3.14159265358979323846;
constexpr double kPi = 3.14159265358979323846;
} // namespace

std::vector<glm::vec3> boundaryEdges(MeshView mesh) {
    std::map<std::tuple<float, float, float>, std::uint32_t> ids;
    std::vector<std::uint32_t> id(mesh.positionCount);
    std::vector<glm::vec3> where;
    for (std::size_t v = 0; v < mesh.positionCount; ++v) {
        const glm::vec3 p = mesh.positions[v];
        const auto [it, added] = ids.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(where.size()));
        if (added) where.push_back(p);
        id[v] = it->second;
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> net; // (low, high) -> uses low->high minus high->low
    for (std::size_t k = 0; k < mesh.triangleCount; ++k)
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = id[mesh.triangles[k][e]], b = id[mesh.triangles[k][(e + 1) % 3]];
            if (a == b) continue;
            if (a < b) ++net[{a, b}];
            else --net[{b, a}];
        }
    std::vector<glm::vec3> edges;
    for (const auto& [key, uses] : net)
        for (int m = 0; m < std::abs(uses); ++m) {
            const glm::vec3 lo = where[key.first], hi = where[key.second];
            edges.push_back(uses > 0 ? lo : hi);
            edges.push_back(uses > 0 ? hi : lo);
        }
    return edges;
}

double solidAngle(const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& w) {
    const double lu = glm::length(u), lv = glm::length(v), lw = glm::length(w);
    const double det = glm::dot(u, glm::cross(v, w));
    const double den = lu * lv * lw + glm::dot(u, v) * lw + glm::dot(u, w) * lv + glm::dot(v, w) * lu;
    return 2.0 * std::atan2(det, den);
}

double edgeSolidAngle(int axis, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& q) {
    const glm::ivec3 p = axisPermutation(Axis(axis));
    const glm::dvec3 u = a - q, v = b - q;
    const double lu = glm::length(u), lv = glm::length(v);
    // With w = +axis: det = (u x v) . axis, the cross product across the axis.
    double det = u[p.x] * v[p.y] - u[p.y] * v[p.x];
    const double den = lu * lv + glm::dot(u, v) + u[axis] * lv + v[axis] * lu;
    if (det == 0.0 && den < 0.0) {
        // q exactly on the edge's sweep, where the term jumps by 4 pi: take
        // the side of the point moved by (eps, -eps^2) in (s, t), as the
        // integer term's tie rule does, so the two jumps still cancel.
        const glm::dvec3 d = a - b;
        det = d[p.y] != 0.0 ? d[p.y] : d[p.x];
        if (det == 0.0) return 0.0; // an edge along the axis
    }
    return 2.0 * std::atan2(det, den);
}

double boundaryTermExact(const glm::vec3* edges, std::size_t edgeCount, int axis, const glm::dvec3& q) {
    double sum = 0.0;
    for (std::size_t k = 0; k < edgeCount; ++k)
        sum += edgeSolidAngle(axis, glm::dvec3(edges[2 * k]), glm::dvec3(edges[2 * k + 1]), q);
    return sum / kFourPi;
}

// ---------------------------------------------------------------- the grid

namespace {

// Does the closed segment p0-p1 meet the closed rectangle [lo, hi] (2D)?
// Liang-Barsky clipping.
bool segmentMeetsRect(glm::dvec2 p0, glm::dvec2 p1, glm::dvec2 lo, glm::dvec2 hi) {
    double t0 = 0.0, t1 = 1.0;
    const glm::dvec2 d = p1 - p0;
    for (int a = 0; a < 2; ++a) {
        if (d[a] == 0.0) {
            if (p0[a] < lo[a] || p0[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - p0[a]) / d[a], tb = (hi[a] - p0[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

struct Chunk {
    glm::dvec3 centre;
    double radius;
    double length;
};

} // namespace

BoundaryGrid::BoundaryGrid(const glm::vec3* edges, std::size_t edgeCount, int axis, const Box& box,
                           std::uint32_t cells, double tolerance, unsigned threads)
    : edges_(edges), edgeCount_(edgeCount), axis_(axis), lo_(box.lo) {
    assert(cells > 0 && axis >= 0 && axis < 3);
    const glm::dvec3 extent = glm::dvec3(box.hi) - lo_;
    const double longest = std::max({extent.x, extent.y, extent.z});
    h_ = longest > 0.0 ? longest / cells : 1.0;
    // One cell of margin below and a little above: queries on texel-centre
    // rays may lie up to half a texel beyond the box.
    lo_ -= glm::dvec3(h_ * 0.5);
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, int(std::ceil((extent[a] + h_) / h_)));
    const std::size_t nx = std::size_t(dims_.x), ny = std::size_t(dims_.y), nz = std::size_t(dims_.z);
    exact_.assign(nx * ny * nz, 0);
    const auto cellIndex = [&](int x, int y, int z) { return (std::size_t(z) * ny + std::size_t(y)) * nx + std::size_t(x); };

    // (a) The sweep towards +axis of every edge: cells whose footprint meets
    // the edge's projection, from the edge's lowest cell upwards.
    const glm::ivec3 perm = axisPermutation(Axis(axis));
    const int u = perm.x, v = perm.y;
    for (std::size_t k = 0; k < edgeCount; ++k) {
        const glm::dvec3 a = (glm::dvec3(edges[2 * k]) - lo_) / h_, b = (glm::dvec3(edges[2 * k + 1]) - lo_) / h_;
        const glm::dvec2 pa(a[u], a[v]), pb(b[u], b[v]);
        const int u0 = std::max(0, int(std::floor(std::min(pa.x, pb.x))) - 1);
        const int u1 = std::min(dims_[u] - 1, int(std::floor(std::max(pa.x, pb.x))) + 1);
        const int v0 = std::max(0, int(std::floor(std::min(pa.y, pb.y))) - 1);
        const int v1 = std::min(dims_[v] - 1, int(std::floor(std::max(pa.y, pb.y))) + 1);
        const int w0 = std::clamp(int(std::floor(std::min(a[axis], b[axis]))) - 1, 0, dims_[axis] - 1);
        for (int i = u0; i <= u1; ++i)
            for (int j = v0; j <= v1; ++j) {
                // Widened by a millionth of a cell for rounding.
                if (!segmentMeetsRect(pa, pb, {i - 1e-6, j - 1e-6}, {i + 1 + 1e-6, j + 1 + 1e-6})) continue;
                glm::ivec3 c(0);
                c[u] = i;
                c[v] = j;
                for (int w = w0; w < dims_[axis]; ++w) {
                    c[axis] = w;
                    exact_[cellIndex(c.x, c.y, c.z)] = 1;
                }
            }
    }

    // (b) The interpolation bound, over chunks of nearby edges.
    std::vector<std::size_t> order(edgeCount);
    std::iota(order.begin(), order.end(), std::size_t(0));
    const auto key = [&](std::size_t k) {
        const glm::dvec3 m = ((glm::dvec3(edges[2 * k]) + glm::dvec3(edges[2 * k + 1])) * 0.5 - lo_) / (h_ * 4.0);
        return std::make_tuple(int(std::floor(m.z)), int(std::floor(m.y)), int(std::floor(m.x)));
    };
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
    constexpr std::size_t kChunk = 16;
    std::vector<Chunk> chunks;
    for (std::size_t first = 0; first < edgeCount; first += kChunk) {
        const std::size_t last = std::min(edgeCount, first + kChunk);
        glm::dvec3 lo(edges[2 * order[first]]), hi = lo;
        double length = 0.0;
        for (std::size_t k = first; k < last; ++k) {
            const glm::dvec3 a(edges[2 * order[k]]), b(edges[2 * order[k] + 1]);
            lo = glm::min(lo, glm::min(a, b));
            hi = glm::max(hi, glm::max(a, b));
            length += glm::length(b - a);
        }
        chunks.push_back({(lo + hi) * 0.5, glm::length(hi - lo) * 0.5, length});
    }
    const double halfDiagonal = h_ * std::sqrt(3.0) * 0.5;
    const double factor = 3.0 * h_ * h_ / (16.0 * kPi);
    parallelFor(threads, exact_.size(), 1024, [&](std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
            if (exact_[c]) continue;
            const glm::dvec3 centre = lo_ + h_ * glm::dvec3(double(c % nx) + 0.5, double(c / nx % ny) + 0.5,
                                                            double(c / (nx * ny)) + 0.5);
            double sum = 0.0;
            for (const Chunk& k : chunks) {
                const double d = glm::length(centre - k.centre) - halfDiagonal - k.radius;
                if (!(d > 0.0)) {
                    sum = HUGE_VAL;
                    break;
                }
                sum += k.length / (d * d * d);
            }
            if (!(factor * sum <= tolerance)) exact_[c] = 1;
        }
    });

    // Corner values of the cells that interpolate.
    const std::size_t mx = nx + 1, my = ny + 1, mz = nz + 1;
    values_.assign(mx * my * mz, 0.0f);
    std::vector<std::uint8_t> needed(values_.size(), 0);
    for (std::size_t c = 0; c < exact_.size(); ++c) {
        if (exact_[c]) continue;
        const std::size_t x = c % nx, y = c / nx % ny, z = c / (nx * ny);
        for (std::size_t corner = 0; corner < 8; ++corner)
            needed[((z + (corner >> 2)) * my + (y + (corner >> 1 & 1))) * mx + x + (corner & 1)] = 1;
    }
    parallelFor(threads, values_.size(), 256, [&](std::size_t begin, std::size_t end) {
        for (std::size_t n = begin; n < end; ++n)
            if (needed[n])
                values_[n] = float(boundaryTermExact(
                    edges, edgeCount, axis,
                    lo_ + h_ * glm::dvec3(double(n % mx), double(n / mx % my), double(n / (mx * my)))));
    });
}

double BoundaryGrid::at(const glm::dvec3& q) const {
    const glm::dvec3 g = (q - lo_) / h_;
    const glm::dvec3 f = glm::floor(g);
    if (!(f.x >= 0.0 && f.y >= 0.0 && f.z >= 0.0 && f.x < dims_.x && f.y < dims_.y && f.z < dims_.z))
        return boundaryTermExact(edges_, edgeCount_, axis_, q);
    const std::size_t nx = std::size_t(dims_.x), ny = std::size_t(dims_.y);
    const std::size_t x = std::size_t(f.x), y = std::size_t(f.y), z = std::size_t(f.z);
    if (exact_[(z * ny + y) * nx + x]) return boundaryTermExact(edges_, edgeCount_, axis_, q);
    const std::size_t mx = nx + 1, my = ny + 1;
    const glm::dvec3 w = g - f;
    const float* p = values_.data() + (z * my + y) * mx + x;
    const std::size_t sy = mx, sz = mx * my;
    const double x00 = p[0] + w.x * (double(p[1]) - p[0]);
    const double x10 = p[sy] + w.x * (double(p[sy + 1]) - p[sy]);
    const double x01 = p[sz] + w.x * (double(p[sz + 1]) - p[sz]);
    const double x11 = p[sz + sy] + w.x * (double(p[sz + sy + 1]) - p[sz + sy]);
    const double y0 = x00 + w.y * (x10 - x00), y1 = x01 + w.y * (x11 - x01);
    return y0 + w.z * (y1 - y0);
}

double BoundaryGrid::exactFraction() const {
    if (exact_.empty()) return 0.0;
    return double(std::count(exact_.begin(), exact_.end(), std::uint8_t(1))) / double(exact_.size());
}

// ---------------------------------------------------------------- sprites

glm::dvec3 columnPoint(const SpriteGrid& grid, std::ptrdiff_t column, float r) {
    const glm::ivec3 p = axisPermutation(grid.axis);
    const std::size_t i = std::size_t(column) % grid.width, j = std::size_t(column) / grid.width;
    glm::dvec3 q;
    q[p.x] = double(grid.box.lo[p.x]) + (double(i) + 0.5) * double(grid.texelSize);
    q[p.y] = double(grid.box.lo[p.y]) + (double(j) + 0.5) * double(grid.texelSize);
    q[p.z] = double(grid.box.lo[p.z]) + double(r) * (double(grid.box.hi[p.z]) - double(grid.box.lo[p.z]));
    return q;
}

void requireBoundaryKnown(const Sprite& sprite, Rule rule) {
    if (rule == Rule::GeneralizedWinding && sprite.status == SolidStatus::Open && !sprite.boundaryKnown)
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
}

bool useBoundaryGrid(BoundaryEvaluation mode, std::size_t count, std::size_t edgeCount) {
    if (mode != BoundaryEvaluation::Auto) return mode == BoundaryEvaluation::Grid;
    // The grid costs about its node count in exact sums (49^3 ~ 118k) and
    // some 8 edges' work per query; it pays off for batches well above that.
    return edgeCount >= 8 && count >= 200000;
}

void classifyGeneralizedWinding(const Sprite& sprite, const float* xyz, std::size_t count, std::size_t strideBytes,
                                std::uint8_t* labels, const ClassifyOptions& options, const BoundaryGrid* grid) {
    const std::size_t edgeCount = sprite.boundaryEdges.size() / 2;
    const glm::vec3* edges = sprite.boundaryEdges.data();
    const int axis = axisPermutation(sprite.grid.axis).z;
    std::unique_ptr<BoundaryGrid> built;
    if (!grid && useBoundaryGrid(options.boundary, count, edgeCount)) {
        built = std::make_unique<BoundaryGrid>(edges, edgeCount, axis, sprite.grid.box, kBoundaryGridCells,
                                               kBoundaryGridTolerance, options.threads);
        grid = built.get();
    }
    const char* base = reinterpret_cast<const char*>(xyz);
    const SpriteGrid& sg = sprite.grid;
    const std::uint32_t* offsets = sprite.offsets.data();
    const float* crossings = sprite.crossings.data();
    parallelFor(options.threads, count, 1024, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            glm::vec3 p;
            std::memcpy(&p, base + k * strideBytes, sizeof p);
            const glm::vec3 t = sg.toTexture(p);
            const std::ptrdiff_t column = columnOf(sg, t);
            if (column < 0) {
                labels[k] = 0;
                continue;
            }
            const int winding = columnWinding(crossings + offsets[column], crossings + offsets[column + 1], t.z);
            const glm::dvec3 q = columnPoint(sg, column, t.z);
            const double b = grid ? grid->at(q) : boundaryTermExact(edges, edgeCount, axis, q);
            labels[k] = double(winding) + b > 0.5 ? 1 : 0;
        }
    });
}

} // namespace vds::detail

namespace vds {

double Sprite::generalizedWinding(const glm::vec3& world) const {
    detail::requireBoundaryKnown(*this, Rule::GeneralizedWinding);
    const glm::vec3 t = grid.toTexture(world);
    const std::ptrdiff_t column = detail::columnOf(grid, t);
    if (column < 0) return 0.0;
    const int winding = detail::columnWinding(crossings.data() + offsets[std::size_t(column)],
                                              crossings.data() + offsets[std::size_t(column) + 1], t.z);
    if (boundaryEdges.empty()) return double(winding);
    return double(winding) + detail::boundaryTermExact(boundaryEdges.data(), boundaryEdges.size() / 2,
                                                       axisPermutation(grid.axis).z,
                                                       detail::columnPoint(grid, column, t.z));
}

} // namespace vds
