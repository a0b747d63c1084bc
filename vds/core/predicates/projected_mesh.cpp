#include <vds/detail/projected_mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include <vds/error.h>

namespace vds::detail {
void CellGrid::setDims(std::uint32_t s, std::uint32_t t) {
    dims_[0] = s;
    dims_[1] = t;
    for (int a = 0; a < 2; ++a)
        scale_[a] = float(std::min(double(dims_[a]) * kSub / extent_[a], double(std::numeric_limits<float>::max())));
}

std::uint64_t CellGrid::countEntries(const std::vector<Box2>& boxes) const {
    std::uint64_t count = 0;
    for (const Box2& b : boxes)
        count += std::uint64_t(fine(b.hi[0], 0) / kSub - fine(b.lo[0], 0) / kSub + 1) *
                 (fine(b.hi[1], 1) / kSub - fine(b.lo[1], 1) / kSub + 1);
    return count;
}

void CellGrid::layout(const std::vector<Box2>& boxes) {
    if (boxes.empty()) return;
    lo_[0] = lo_[1] = std::numeric_limits<float>::max();
    hi_[0] = hi_[1] = -std::numeric_limits<float>::max();
    std::vector<float> widths(boxes.size()), heights(boxes.size());
    for (std::size_t k = 0; k < boxes.size(); ++k) {
        const Box2& b = boxes[k];
        for (int a = 0; a < 2; ++a) {
            lo_[a] = std::min(lo_[a], b.lo[a]);
            hi_[a] = std::max(hi_[a], b.hi[a]);
        }
        widths[k] = b.hi[0] - b.lo[0];
        heights[k] = b.hi[1] - b.lo[1];
    }
    // A crossable triangle has a projected area, so both extents are > 0.
    for (int a = 0; a < 2; ++a) extent_[a] = double(hi_[a]) - double(lo_[a]);
    // About kCellsPerTriangle cells per triangle, shaped like the median
    // triangle's box, so that long thin triangles get long thin cells.
    const auto median = [](std::vector<float>& v) {
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return double(v[v.size() / 2]);
    };
    const double width = median(widths), height = median(heights);
    const double aspect = width > 0.0 && height > 0.0 ? width / height : 1.0;
    const double cells = kCellsPerTriangle * double(boxes.size()) + 16.0;
    const double s = std::sqrt(cells * extent_[0] / (extent_[1] * aspect));
    constexpr double kMaxDim = 1 << 15;
    const auto dim = [&](double d) { return std::uint32_t(std::clamp(std::ceil(d), 1.0, kMaxDim)); };
    setDims(dim(s), dim(cells / s));
    // Boxes spanning many cells (long thin triangles across the grid): coarsen
    // until the entries stay linear in the triangle count.
    const std::uint64_t maxEntries = 16 * std::uint64_t(boxes.size()) + 1024;
    while ((dims_[0] > 1 || dims_[1] > 1) && countEntries(boxes) > maxEntries)
        setDims((dims_[0] + 1) / 2, (dims_[1] + 1) / 2);
}

void CellGrid::fill(const std::vector<Box2>& boxes, const std::vector<float>& depthLo) {
    if (boxes.empty()) return;
    const std::size_t cellCount = std::size_t(dims_[0]) * dims_[1];
    offsets_.assign(cellCount + 1, 0);
    for (const Box2& b : boxes)
        for (std::uint32_t j = fine(b.lo[1], 1) / kSub, j1 = fine(b.hi[1], 1) / kSub; j <= j1; ++j)
            for (std::uint32_t i = fine(b.lo[0], 0) / kSub, i1 = fine(b.hi[0], 0) / kSub; i <= i1; ++i)
                ++offsets_[std::size_t(j) * dims_[0] + i + 1];
    std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
    entries_.resize(offsets_.back());
    std::vector<std::size_t> next(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
        const std::uint32_t lo[2] = {fine(boxes[k].lo[0], 0), fine(boxes[k].lo[1], 1)};
        const std::uint32_t hi[2] = {fine(boxes[k].hi[0], 0), fine(boxes[k].hi[1], 1)};
        for (std::uint32_t j = lo[1] / kSub; j <= hi[1] / kSub; ++j)
            for (std::uint32_t i = lo[0] / kSub; i <= hi[0] / kSub; ++i) {
                CellEntry e;
                e.triangle = std::uint32_t(k);
                e.lo[0] = std::uint8_t(i == lo[0] / kSub ? lo[0] % kSub : 0);
                e.hi[0] = std::uint8_t(i == hi[0] / kSub ? hi[0] % kSub : kSub - 1);
                e.lo[1] = std::uint8_t(j == lo[1] / kSub ? lo[1] % kSub : 0);
                e.hi[1] = std::uint8_t(j == hi[1] / kSub ? hi[1] % kSub : kSub - 1);
                e.depthLo = depthLo[k];
                entries_[next[std::size_t(j) * dims_[0] + i]++] = e;
            }
    }
    // Nearest first; equal depths by triangle, so the layout is reproducible.
    for (std::size_t c = 0; c < cellCount; ++c)
        std::sort(entries_.begin() + std::ptrdiff_t(offsets_[c]), entries_.begin() + std::ptrdiff_t(offsets_[c + 1]),
                  [](const CellEntry& a, const CellEntry& b) {
                      return a.depthLo < b.depthLo || (a.depthLo == b.depthLo && a.triangle < b.triangle);
                  });
}

ProjectedMesh::ProjectedMesh(MeshView mesh, Axis viewAxis) : axis(viewAxis), perm(axisPermutation(viewAxis)) {
    const std::size_t n = mesh.triangleCount;
    if (n > std::numeric_limits<std::uint32_t>::max()) throw InvalidMesh("mesh has more than 2^32 - 1 triangles");
    std::vector<Triangle> all(n);
    std::vector<std::uint32_t> crossing; // indices into `all`
    std::vector<Box2> boxes;             // of `crossing`
    for (std::size_t k = 0; k < n; ++k) {
        Triangle& t = all[k];
        t = projectTriangle(mesh, k, perm);
        if (!(t.flags & kParallel)) {
            crossing.push_back(std::uint32_t(k));
            boxes.push_back(boxOf(t));
        }
    }
    crossable = crossing.size();
    grid.layout(boxes);

    // Crossable triangles first, in the order of their boxes' centre cells,
    // so that the candidates of one query lie close together in memory.
    std::vector<std::pair<std::size_t, std::uint32_t>> order(crossable);
    for (std::size_t k = 0; k < crossable; ++k) {
        const Box2& b = boxes[k];
        const float centre[2] = {0.5f * b.lo[0] + 0.5f * b.hi[0], 0.5f * b.lo[1] + 0.5f * b.hi[1]};
        order[k] = {grid.cellIndex(centre), std::uint32_t(k)};
    }
    std::sort(order.begin(), order.end());
    tris.reserve(n);
    std::vector<Box2> sortedBoxes(crossable);
    std::vector<float> depthLo(crossable);
    for (std::size_t k = 0; k < crossable; ++k) {
        const Triangle& t = all[crossing[order[k].second]];
        tris.push_back(t);
        sortedBoxes[k] = boxes[order[k].second];
        depthLo[k] = std::min({t.v[0][2], t.v[1][2], t.v[2][2]});
    }
    for (const Triangle& t : all)
        if (t.flags & kParallel) tris.push_back(t);
    grid.fill(sortedBoxes, depthLo);
}

} // namespace vds::detail
