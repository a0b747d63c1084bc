// vds: the boundary term over one cell as its near edges' angles plus the
// interpolated rest (cell_field.h says why it is exact to its bound).
#include <vds/detail/cell_field.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <glm/geometric.hpp>

#include <vds/detail/antipodal.h>
#include <vds/detail/chain_labels.h>
#include <vds/detail/caps_math.h>
#include <vds/detail/tree_walk.h>

namespace vds::detail {

namespace {

/// The chain tree's tolerance on a node for the samples (ChainLabels::sum):
/// their summed bounds enter the field's error times (5/4)^3, so small
/// against the interpolation's.
constexpr double kSampleTolerance = 2e-5;
/// Quadratic interpolation at -s, 0, s: max |x (x^2 - s^2)| / 6 over
/// [-s, s] is 2 / (3 sqrt 3) / 6 = 0.06415 s^3 (rounded up), and the
/// Lebesgue constant 5/4.
constexpr double kQuadraticError = 0.0642;
constexpr double kLebesgue = 1.25;

/// A rectangle across the axis: the footprint of a box.
struct Rect {
    double s0, s1, t0, t1;
};

double pointRectDistance(double s, double t, const Rect& r) {
    const double ds = std::max({r.s0 - s, 0.0, s - r.s1}), dt = std::max({r.t0 - t, 0.0, t - r.t1});
    return std::sqrt(ds * ds + dt * dt);
}

double pointSegmentDistance(double s, double t, double as, double at, double bs, double bt) {
    const double ds = bs - as, dt = bt - at, length2 = ds * ds + dt * dt;
    double u = length2 > 0.0 ? ((s - as) * ds + (t - at) * dt) / length2 : 0.0;
    u = std::clamp(u, 0.0, 1.0);
    const double es = as + u * ds - s, et = at + u * dt - t;
    return std::sqrt(es * es + et * et);
}

/// Whether segment a -> b (across the axis) meets the rectangle
/// (Liang-Barsky's clip).
bool segmentMeetsRect(double as, double at, double bs, double bt, const Rect& r) {
    double from = 0.0, to = 1.0;
    const double p[4] = {-(bs - as), bs - as, -(bt - at), bt - at};
    const double q[4] = {as - r.s0, r.s1 - as, at - r.t0, r.t1 - at};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) return false;
            continue;
        }
        const double u = q[k] / p[k];
        if (p[k] < 0.0) from = std::max(from, u);
        else to = std::min(to, u);
        if (from > to) return false;
    }
    return true;
}

/// Distance across the axis from segment a -> b to the rectangle.
double segmentRectDistance(double as, double at, double bs, double bt, const Rect& r) {
    if (segmentMeetsRect(as, at, bs, bt, r)) return 0.0;
    double d = std::min(pointRectDistance(as, at, r), pointRectDistance(bs, bt, r));
    for (const double s : {r.s0, r.s1})
        for (const double t : {r.t0, r.t1}) d = std::min(d, pointSegmentDistance(s, t, as, at, bs, bt));
    return d;
}

/// Distance from the box of segment a -> b to the box [lo, hi]: at most
/// the segment's distance to it.
double boxDistance(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& lo, const glm::dvec3& hi) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double gap = std::max({lo[k] - std::max(a[k], b[k]), 0.0, std::min(a[k], b[k]) - hi[k]});
        sum += gap * gap;
    }
    return std::sqrt(sum);
}

} // namespace

void CellField::split(const ChainLabels& labels, const glm::dvec3& lo, const glm::dvec3& hi, double margin,
                      std::vector<std::uint32_t>& far) {
    const int a = labels.axisIndex(), s = (a + 1) % 3, t = (a + 2) % 3;
    const Rect rect{lo[s], hi[s], lo[t], hi[t]};
    const std::vector<ChainNode>& chains = labels.chains();
    // True where every edge under node i is near (the caller may keep the
    // node whole); else its far nodes into `far`, its wholly near
    // children into `whole`.
    std::vector<std::uint32_t> whole;
    const std::function<bool(std::uint32_t)> cut = [&](std::uint32_t i) {
        const ChainNode& n = chains[i];
        work_ += 1.0;
        // The ball's footprint (widened against rounding) against the margin.
        if (pointRectDistance(n.centre[s], n.centre[t], rect) - n.radius * (1.0 + 1e-9) >= margin) {
            far.push_back(i);
            return false;
        }
        if (n.count != 0 || n.edgeCount <= caps::kDirectEdges) return true;
        const bool left = cut(n.left), right = cut(n.right);
        if (left && right) return true;
        if (left) whole.push_back(n.left);
        if (right) whole.push_back(n.right);
        return false;
    };
    if (cut(0)) whole.push_back(0);
    // Split where no query in the box could take the node (the chain
    // tree's frontier): what refine() would split at every query.
    const glm::dvec3 centre = 0.5 * (lo + hi);
    labels.frontier(whole.data(), whole.size(), centre, 0.5 * glm::length(hi - lo), near_);
}

double CellField::thirdBound(const ChainLabels& labels, const std::vector<std::uint32_t>& far,
                             const glm::dvec3& lo, const glm::dvec3& hi) {
    const int a = labels.axisIndex(), s = (a + 1) % 3, t = (a + 2) % 3;
    const Rect rect{lo[s], hi[s], lo[t], hi[t]};
    const std::vector<ChainNode>& chains = labels.chains();
    const std::vector<glm::vec3>& edges = labels.edges();
    // Lower bounds on distances: shrunk against their rounding.
    constexpr double kShrink = 1.0 - 1e-9;
    double edgeSum = 0.0, raySum = 0.0, work = 0.0;
    // The far nodes' edges: a node small against its distance (its edges
    // lie within kWhole of it) by its length, else its children, a
    // leaf's edges one by one.
    constexpr double kWhole = 0.125;
    for (const std::uint32_t root : far)
        walkTree(root, [&](std::uint32_t i, TreeStack& stack) {
            const ChainNode& n = chains[i];
            const double reach = n.radius * (1.0 + 1e-12);
            const double d = (std::max(pointRectDistance(n.centre[s], n.centre[t], rect),
                                       boxDistance(n.centre, n.centre, lo, hi)) - reach) * kShrink;
            work += 1.0;
            if (reach <= kWhole * d) {
                edgeSum += labels.lengthOf(n) / kShrink / (d * d * d * d);
            } else if (n.count == 0 && n.edgeCount > caps::kDirectEdges) {
                stack.push(n.left);
                stack.push(n.right);
            } else {
                work += double(n.edgeCount);
                for (std::size_t k = n.edgeFirst; k < n.edgeFirst + n.edgeCount; ++k) {
                    const glm::dvec3 p(edges[2 * k]), q(edges[2 * k + 1]);
                    const double across = segmentRectDistance(p[s], p[t], q[s], q[t], rect);
                    const double e = std::max(across, boxDistance(p, q, lo, hi)) * kShrink, e2 = e * e;
                    edgeSum += glm::length(q - p) / kShrink / (e2 * e2);
                }
            }
            return true;
        });
    // The junctions: where a near node's run of a loop meets a far edge,
    // a ray at the shared vertex, as far across the axis as that edge.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> runs; // near edges [first, end)
    for (const std::uint32_t i : near_)
        runs.emplace_back(chains[i].edgeFirst, chains[i].edgeFirst + chains[i].edgeCount);
    std::sort(runs.begin(), runs.end());
    const auto isNear = [&](std::uint32_t edge) {
        const auto at = std::upper_bound(runs.begin(), runs.end(), std::make_pair(edge, ~0u));
        return at != runs.begin() && edge < (at - 1)->second;
    };
    const auto addRay = [&](const glm::vec3& vertex) {
        const double rho = pointRectDistance(vertex[s], vertex[t], rect) * kShrink;
        raySum += 0.5 * kPi / (rho * rho * rho);
    };
    for (const auto& [first, end] : runs) {
        const auto [loopFirst, loopEnd] = labels.loopOf(first);
        const std::uint32_t before = first == loopFirst ? loopEnd - 1 : first - 1;
        const std::uint32_t after = end == loopEnd ? loopFirst : end;
        if (!isNear(before)) addRay(edges[2 * std::size_t(first)]);
        if (!isNear(after)) addRay(edges[2 * std::size_t(end - 1) + 1]);
    }
    work_ += work + double(runs.size());
    return 6.0 * std::sqrt(2.0) / kFourPi * (edgeSum + raySum);
}

bool CellField::build(const ChainLabels& labels, const glm::dvec3& lo, const glm::dvec3& hi, double margin,
                      double limit, std::size_t nearLimit) {
    if (labels.chains().empty() || !(margin > 0.0)) return false;
    std::vector<std::uint32_t> far;
    split(labels, lo, hi, margin, far);
    if (near_.size() >= nearLimit) return false;
    const double third = thirdBound(labels, far, lo, hi);
    const glm::dvec3 spacing = 0.25 * (hi - lo);
    // The interpolation's error in an octant: the largest axis first (weight 1).
    double axisError[3];
    for (int k = 0; k < 3; ++k) axisError[k] = kQuadraticError * spacing[k] * spacing[k] * spacing[k] * third;
    std::sort(axisError, axisError + 3, std::greater<double>());
    const double interpolation = axisError[0] + kLebesgue * axisError[1] + kLebesgue * kLebesgue * axisError[2];
    if (!(interpolation < limit)) return false;
    lo_ = lo;
    for (int k = 0; k < 3; ++k) inverse_[k] = spacing[k] > 0.0 ? 1.0 / spacing[k] : 0.0;
    std::array<glm::dvec3, 125> nodes;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            for (int k = 0; k < 5; ++k) nodes[std::size_t(25 * i + 5 * j + k)] = lo + glm::dvec3(i, j, k) * spacing;
    double sampling = 0.0;
    const double sampleError =
        labels.sumOver(far.data(), far.size(), lo, hi, nodes.data(), nodes.size(), kSampleTolerance,
                       values_.data(), sampling);
    work_ += sampling;
    error_ = (interpolation + kLebesgue * kLebesgue * kLebesgue * sampleError) * (1.0 + 1e-9) + caps::kRoundingSlack;
    return error_ < limit;
}

double CellField::rest(const glm::vec3& q) const {
    const glm::dvec3 p(q);
    double weight[3][3];
    int first[3];
    for (int a = 0; a < 3; ++a) {
        // The octant's nodes 2 o .. 2 o + 2, Lagrange's weights at u = -1, 0, 1.
        const double x = (p[a] - lo_[a]) * inverse_[a];
        first[a] = x >= 2.0 ? 2 : 0;
        const double u = x - double(first[a]) - 1.0;
        weight[a][0] = 0.5 * u * (u - 1.0);
        weight[a][1] = 1.0 - u * u;
        weight[a][2] = 0.5 * u * (u + 1.0);
    }
    double sum = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double* row = values_.data() + 25 * (first[0] + i) + 5 * (first[1] + j) + first[2];
            const double along = weight[2][0] * row[0] + weight[2][1] * row[1] + weight[2][2] * row[2];
            sum += weight[0][i] * weight[1][j] * along;
        }
    return sum;
}

} // namespace vds::detail
