#include <vds/eval/distance.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace vds::eval {

double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    // Ericson 2005, ClosestPtPointTriangle: Voronoi regions of the vertices,
    // the edges, then the face.
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return glm::length(p - a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return glm::length(p - b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return glm::length(p - c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) // degenerate triangle: the nearest of its edges
        return std::min({glm::length(p - a), glm::length(p - b), glm::length(p - c)});
    const double v = vb / sum, w = vc / sum;
    return glm::length(p - (a + ab * v + ac * w));
}

SurfaceDistance::SurfaceDistance(MeshView mesh) {
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= mesh.positionCount || tri.y >= mesh.positionCount || tri.z >= mesh.positionCount) continue;
        for (int k = 0; k < 3; ++k) corners_.emplace_back(mesh.positions[tri[k]]);
    }
    const std::size_t n = corners_.size() / 3;
    if (n == 0) return;
    glm::dvec3 hi = corners_[0];
    lo_ = corners_[0];
    for (const auto& c : corners_) {
        lo_ = glm::min(lo_, c);
        hi = glm::max(hi, c);
    }
    // About two triangles per cell, at most 128 cells per axis.
    const glm::dvec3 extent = glm::max(hi - lo_, glm::dvec3(1e-12));
    const double volume = extent.x * extent.y * extent.z;
    const double side = std::cbrt(volume * 2.0 / double(n));
    for (int a = 0; a < 3; ++a) {
        dims_[a] = int(std::clamp(std::ceil(extent[a] / side), 1.0, 128.0));
        cell_[a] = extent[a] / dims_[a];
    }
    const auto cellOf = [&](const glm::dvec3& p) {
        glm::ivec3 c;
        for (int a = 0; a < 3; ++a) c[a] = std::clamp(int((p[a] - lo_[a]) / cell_[a]), 0, dims_[a] - 1);
        return c;
    };
    const std::size_t cells = std::size_t(dims_.x) * dims_.y * dims_.z;
    offsets_.assign(cells + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
        for (std::size_t t = 0; t < n; ++t) {
            const glm::dvec3* v = &corners_[3 * t];
            const glm::ivec3 a = cellOf(glm::min(v[0], glm::min(v[1], v[2])));
            const glm::ivec3 b = cellOf(glm::max(v[0], glm::max(v[1], v[2])));
            for (int z = a.z; z <= b.z; ++z)
                for (int y = a.y; y <= b.y; ++y)
                    for (int x = a.x; x <= b.x; ++x) {
                        const std::size_t c = (std::size_t(z) * dims_.y + y) * dims_.x + x;
                        if (pass == 0)
                            ++offsets_[c + 1];
                        else
                            refs_[fill[c]++] = std::uint32_t(t);
                    }
        }
        if (pass == 0) {
            for (std::size_t c = 0; c < cells; ++c) offsets_[c + 1] += offsets_[c];
            refs_.resize(offsets_.back());
        }
    }
}

double SurfaceDistance::distance(const glm::vec3& point) const {
    if (corners_.empty()) return std::numeric_limits<double>::infinity();
    const glm::dvec3 p(point);
    // Rings of cells around the cell of p's projection onto the grid's box:
    // after ring r, every unvisited triangle is at least r cells away.
    glm::ivec3 centre;
    for (int a = 0; a < 3; ++a) centre[a] = std::clamp(int(std::floor((p[a] - lo_[a]) / cell_[a])), 0, dims_[a] - 1);
    const double step = std::min({cell_.x, cell_.y, cell_.z});
    const int rings = std::max({dims_.x, dims_.y, dims_.z});
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= rings; ++r) {
        for (int z = centre.z - r; z <= centre.z + r; ++z) {
            if (z < 0 || z >= dims_.z) continue;
            for (int y = centre.y - r; y <= centre.y + r; ++y) {
                if (y < 0 || y >= dims_.y) continue;
                const bool faceZY = std::abs(z - centre.z) == r || std::abs(y - centre.y) == r;
                for (int x = centre.x - r; x <= centre.x + r; x += (faceZY || r == 0) ? 1 : 2 * r) {
                    if (x < 0 || x >= dims_.x) continue;
                    const std::size_t c = (std::size_t(z) * dims_.y + y) * dims_.x + x;
                    for (std::uint32_t k = offsets_[c]; k < offsets_[c + 1]; ++k) {
                        const glm::dvec3* v = &corners_[3 * std::size_t(refs_[k])];
                        best = std::min(best, pointTriangleDistance(p, v[0], v[1], v[2]));
                    }
                }
            }
        }
        if (best <= double(r) * step) break;
    }
    return best;
}

} // namespace vds::eval
