// vds_peers_bench: regular grids of query points, and the sprite's answers
// for a whole grid by one walk down each column ("sweep").
//
// A grid asks N^3 points, but along the sprite's view axis its cells share
// one LDI column per (i, j): instead of N^3 independent lookups (two cache
// misses each, then a scan of the column), the sweep reads each column once
// and moves one pointer through its crossings as k grows. It gives exactly
// `vds::classify`'s answers on the cell centres (same float arithmetic), in
// time O(N^3 + crossings of the columns used). Written here, on the public
// `Sprite` arrays, because only this benchmark needs it so far.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds::peers {

/// n x n x n cells over `box` (not cubic: each axis is cut into n). The
/// centre of cell (i, j, k) is box.lo + (i + 1/2, j + 1/2, k + 1/2) *
/// (box.hi - box.lo) / n, computed in float exactly as `centre` does.
struct CellGrid {
    Box box;
    std::uint32_t n = 0;

    glm::vec3 step() const { return (box.hi - box.lo) / float(n); }
    glm::vec3 centre(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
        return box.lo + glm::vec3(float(i) + 0.5f, float(j) + 0.5f, float(k) + 0.5f) * step();
    }
    std::size_t cellCount() const { return std::size_t(n) * n * n; }
};

/// Centres of the cells of layers k in [k0, k1) into `out`, cell (i, j, k) at
/// index ((k - k0) * n + j) * n + i. `out` holds (k1 - k0) * n * n points.
void cellCentres(const CellGrid& cells, std::uint32_t k0, std::uint32_t k1, glm::vec3* out, unsigned threads);

/// `vds::classify(sprite, ...)` with `Rule::Parity` on the centres of layers
/// [k0, k1), same layout as `cellCentres`, into `labels` ((k1 - k0) * n * n
/// bytes), without the points: one walk per column. The sprite must look
/// along z and be untransformed (as `bake` returns it); throws
/// `InvalidArgument` otherwise.
void sweepSprite(const Sprite& sprite, const CellGrid& cells, std::uint32_t k0, std::uint32_t k1,
                 std::uint8_t* labels, unsigned threads);

} // namespace vds::peers
