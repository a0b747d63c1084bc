// vds: the boundary term of the Antipodal split of the generalized winding
// number (Martens, Trettner & Bessmeltsev, SIGGRAPH 2026, arXiv 2605.01536),
// for sprites, the exact classifier and the voxelizers; see antipodal.h.
#include "antipodal.h"

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
#include <vds/detail/parallel.h>

#include "caps_tree.h"
#include "vpt.h"

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
    // axisPermutation(Axis(axis)), inline: this runs once per edge and point.
    const glm::ivec3 p((axis + 1) % 3, (axis + 2) % 3, axis);
    // Float ends and point: these differences are exact in double, so the
    // tests for zero below are exact.
    const glm::dvec3 u = a - q, v = b - q;
    // An end exactly on q's ray (straight in front of q along -axis): the
    // spherical triangle has a vertex at the antipode of the apex, where it
    // is not defined. Take the limit at q moved by (eps, -eps^2) in (s, t),
    // the integer term's tie rule: with u = (0, 0, -h), to first order in
    // eps det = -eps v_t and den = -eps v_s (u', v' the moved vectors; the
    // (|u'| + u'_r) factor is O(eps^2)), so the angle is 2 atan2(-v_t, -v_s);
    // with v on the ray, det = eps u_t and den = -eps u_s. Where the leading
    // det vanishes the eps^2 term (-eps^2 v_s, eps^2 u_s) has the sign of the
    // +0.0 or -0.0 passed to atan2. An edge along q's line adds 0.
    const bool uOnRay = u[p.x] == 0.0 && u[p.y] == 0.0 && u[axis] < 0.0;
    const bool vOnRay = v[p.x] == 0.0 && v[p.y] == 0.0 && v[axis] < 0.0;
    if (uOnRay || vOnRay) {
        const glm::dvec3& other = uOnRay ? v : u;
        if (other[p.x] == 0.0 && other[p.y] == 0.0) return 0.0; // the edge lies along q's line
        return uOnRay ? 2.0 * std::atan2(-v[p.y], -v[p.x]) : 2.0 * std::atan2(u[p.y], -u[p.x]);
    }
    const double lu = glm::length(u), lv = glm::length(v);
    // With w = +axis: det = (u x v) . axis, the cross product across the axis.
    const double det = u[p.x] * v[p.y] - u[p.y] * v[p.x];
    // Van Oosterom & Strackee's denominator |u||v| + u.v + u_r |v| + v_r |u|
    // is (|u| + u_r)(|v| + v_r) + u_s v_s + u_t v_t. Near q's ray (u_r close
    // to -|u|) the factor |u| + u_r cancels; there it is taken as the equal
    // rho^2 / (|u| - u_r), rho^2 = u_s^2 + u_t^2, which does not: so that an
    // edge seen almost straight along the ray still gets its angle to
    // rounding, not to the square root of it.
    const auto towardsApex = [&](const glm::dvec3& w, double length) {
        return w[axis] >= 0.0 ? length + w[axis] : (w[p.x] * w[p.x] + w[p.y] * w[p.y]) / (length - w[axis]);
    };
    const double den = towardsApex(u, lu) * towardsApex(v, lv) + u[p.x] * v[p.x] + u[p.y] * v[p.y];
    if (det == 0.0 && den < 0.0) {
        // q exactly on the edge's sweep (its ray passes over the edge), where
        // the term jumps by 4 pi: take the side of q moved by (eps, -eps^2)
        // in (s, t), as the integer term's tie rule does, so that the two
        // jumps still cancel. There det = eps (u - v)_t + eps^2 (u - v)_s +
        // O(eps^3) -> 0 with that sign while den stays negative: the angle
        // is +-2 pi.
        const glm::dvec3 d = a - b;
        const double side = d[p.y] != 0.0 ? d[p.y] : d[p.x];
        if (side == 0.0) return 0.0; // an edge along the axis
        return side > 0.0 ? 2.0 * kPi : -2.0 * kPi;
    }
    return 2.0 * std::atan2(det, den);
}

double boundaryTermExact(const glm::vec3* edges, std::size_t edgeCount, int axis, const glm::dvec3& q) {
    // Two sums a sign, alternating, so that consecutive multiplies do not
    // wait on each other; the edges edgeSolidAngle treats apart (det = 0,
    // an end on q's ray) summed as it gives them.
    AngleSum sums[4];
    double apart = 0.0;
    for (std::size_t k = 0; k < edgeCount; ++k) {
        const glm::dvec3 a(edges[2 * k]), b(edges[2 * k + 1]);
        double x, y;
        if (!edgeAngleFactor(axis, a, b, q, x, y)) {
            apart += edgeSolidAngle(axis, a, b, q);
            continue;
        }
        sums[(y > 0.0 ? 0 : 2) + (k & 1)].add(x, std::fabs(y));
    }
    // Each edge adds 2 atan2(det, den).
    const double angles = 2.0 * (sums[0].angle() + sums[1].angle() - sums[2].angle() - sums[3].angle());
    return (angles + apart) / kFourPi;
}

// ---------------------------------------------------------------- sprites

glm::vec3 columnPoint(const SpriteGrid& grid, std::ptrdiff_t column, float r) {
    return grid.texelCentre(std::uint32_t(std::size_t(column) % grid.width),
                            std::uint32_t(std::size_t(column) / grid.width), r);
}

namespace {

/// The texel column of texture point `t` whatever its depth; -1 outside the
/// texture across the axis (or not finite).
std::ptrdiff_t columnAcross(const SpriteGrid& grid, const glm::vec3& t) {
    const float fs = std::floor(t.x * float(grid.width));
    const float ft = std::floor(t.y * float(grid.height));
    if (!(fs >= 0.0f && fs < float(grid.width) && ft >= 0.0f && ft < float(grid.height))) return -1;
    return std::ptrdiff_t(ft) * std::ptrdiff_t(grid.width) + std::ptrdiff_t(fs);
}

/// The generalized winding number of an open mesh need not vanish outside
/// the sprite's box (just beyond a large opening it exceeds 1/2), so GWN
/// queries are answered everywhere: `winding` and `point` get the integer
/// term and the point (mesh coordinates) the boundary term is taken at. In
/// front of or behind the box, the texel's column with none or all of its
/// crossings in front, at its centre as inside the box; beside the box, no
/// crossing (no ray there meets the mesh) at the point itself. False for a
/// point that is not finite.
bool gwnSample(const SpriteGrid& grid, const std::uint32_t* offsets, const float* crossings, const glm::vec3& t,
               std::ptrdiff_t column, int& winding, glm::vec3& point) {
    if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z))) return false;
    if (column >= 0) {
        winding = columnWinding(crossings + offsets[column], crossings + offsets[column + 1], t.z);
        point = columnPoint(grid, column, t.z);
        return true;
    }
    const glm::ivec3 p = axisPermutation(grid.axis);
    winding = 0;
    point[p.x] = grid.box.lo[p.x] + t.x * float(grid.width) * grid.texelSize;
    point[p.y] = grid.box.lo[p.y] + t.y * float(grid.height) * grid.texelSize;
    point[p.z] = grid.box.lo[p.z] + t.z * (grid.box.hi[p.z] - grid.box.lo[p.z]);
    return true;
}

} // namespace

void requireBoundaryKnown(const Sprite& sprite, Rule rule) {
    if (rule == Rule::GeneralizedWinding && sprite.status == SolidStatus::Open && !sprite.boundaryKnown)
        throw InvalidArgument("this sprite of an open mesh was written by .vds format version 1, which does not "
                              "store the boundary edges the generalized winding number needs: bake it again");
}

void classifyGeneralizedWinding(const Sprite& sprite, const float* xyz, std::size_t count, std::size_t strideBytes,
                                std::uint8_t* labels, const ClassifyOptions& options) {
    const std::size_t edgeCount = sprite.boundaryEdges.size() / 2;
    const glm::vec3* edges = sprite.boundaryEdges.data();
    const int axis = axisPermutation(sprite.grid.axis).z;
    const BoundaryCaps* caps = options.boundary == BoundaryEvaluation::Caps
                                   ? &sprite.boundaryCaps.get(sprite.boundaryEdges, sprite.grid.axis, &sprite.grid.box)
                                   : nullptr;
    const char* base = reinterpret_cast<const char*>(xyz);
    const SpriteGrid& sg = sprite.grid;
    const std::uint32_t* offsets = sprite.offsets.data();
    const float* crossings = sprite.crossings.data();
    parallelFor(options.threads, count, 1024, [&](std::size_t begin, std::size_t end) {
        // In batches, so that the cache misses of many points overlap: find
        // a batch's columns and prefetch their offsets, then prefetch their
        // crossings, then label.
        constexpr std::size_t kBatch = 16;
        glm::vec3 texture[kBatch];
        std::ptrdiff_t columns[kBatch];
        for (std::size_t b0 = begin; b0 < end; b0 += kBatch) {
            const std::size_t n = std::min(kBatch, end - b0);
            for (std::size_t i = 0; i < n; ++i) {
                glm::vec3 p;
                std::memcpy(&p, base + (b0 + i) * strideBytes, sizeof p);
                texture[i] = sg.toTexture(p);
                columns[i] = columnAcross(sg, texture[i]);
                if (columns[i] >= 0) __builtin_prefetch(offsets + columns[i]);
            }
            for (std::size_t i = 0; i < n; ++i)
                if (columns[i] >= 0) __builtin_prefetch(crossings + offsets[columns[i]]);
            for (std::size_t i = 0; i < n; ++i) {
                const std::size_t k = b0 + i;
                int winding = 0;
                glm::vec3 q;
                if (!gwnSample(sg, offsets, crossings, texture[i], columns[i], winding, q)) {
                    labels[k] = 0;
                    continue;
                }
                labels[k] = (caps ? caps->inside(winding, q)
                                  : generalizedWindingInside(double(winding) +
                                                             boundaryTermExact(edges, edgeCount, axis, glm::dvec3(q))))
                                ? 1
                                : 0;
            }
        }
    });
}

bool containsGeneralizedWinding(const Sprite& sprite, const glm::vec3& world) {
    requireBoundaryKnown(sprite, Rule::GeneralizedWinding);
    const SpriteGrid& sg = sprite.grid;
    const glm::vec3 t = sg.toTexture(world);
    int winding = 0;
    glm::vec3 q;
    if (!gwnSample(sg, sprite.offsets.data(), sprite.crossings.data(), t, columnAcross(sg, t), winding, q)) return false;
    return sprite.boundaryCaps.get(sprite.boundaryEdges, sg.axis, &sg.box).inside(winding, q);
}

} // namespace vds::detail

namespace vds {

std::vector<glm::vec3> meshBoundaryEdges(MeshView mesh) { return detail::boundaryEdges(mesh); }

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
    if (!detail::gwnSample(grid, offsets.data(), crossings.data(), t, detail::columnAcross(grid, t), winding, q))
        return 0.0;
    return boundaryCaps.get(boundaryEdges, grid.axis, &grid.box).generalizedWinding(winding, q, detail::kGeneralizedWindingTolerance);
}

} // namespace vds
