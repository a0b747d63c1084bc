// The column walk of Trapp & Döllner's volumetric parity test (2008, section
// 3.2) for a whole grid of points at once. The arithmetic is `vds::classify`'s
// (SpriteGrid::toTexture, then the column and depth tests of sprite.cpp), so
// the answers are the same bit for bit; only the order of work differs.
#include "grid_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <vds/error.h>
#include <vds/parallel.h>

namespace vds::peers {

namespace {

// True when the sprite's matrix maps x, y, z to s, t, r alone (a z-view, as
// baked): then s depends on the point's x only, t on y, r on z.
bool zViewUntransformed(const SpriteGrid& g) {
    if (g.axis != Axis::Z) return false;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (c != r && g.matrix[c][r] != 0.0f) return false;
    return true;
}

} // namespace

void cellCentres(const CellGrid& cells, std::uint32_t k0, std::uint32_t k1, glm::vec3* out, unsigned threads) {
    const std::uint32_t n = cells.n;
    const std::size_t rows = std::size_t(k1 - k0) * n;
    parallelFor(threads, rows, 256, [&](std::size_t begin, std::size_t end) {
        for (std::size_t row = begin; row < end; ++row) {
            const std::uint32_t k = k0 + std::uint32_t(row / n), j = std::uint32_t(row % n);
            glm::vec3* p = out + row * n;
            for (std::uint32_t i = 0; i < n; ++i) p[i] = cells.centre(i, j, k);
        }
    });
}

void sweepSprite(const Sprite& sprite, const CellGrid& cells, std::uint32_t k0, std::uint32_t k1,
                 std::uint8_t* labels, unsigned threads) {
    const SpriteGrid& g = sprite.grid;
    if (!zViewUntransformed(g)) throw InvalidArgument("sweepSprite: the sprite must look along z, untransformed");
    const std::uint32_t n = cells.n;
    const std::size_t layer = std::size_t(n) * n;

    // r depends on k alone and never decreases with it (float rounding is
    // monotone), so each column's pointer only moves forward.
    std::vector<float> depth(k1 - k0);
    for (std::uint32_t k = k0; k < k1; ++k) depth[k - k0] = g.toTexture(cells.centre(0, 0, k)).z;

    const float* crossings = sprite.crossings.data();
    const std::uint32_t* offsets = sprite.offsets.data();
    const std::size_t rowsPerChunk = std::max<std::size_t>(1, (std::size_t(1) << 16) / (std::size_t(n) * (k1 - k0)));
    parallelFor(threads, n, rowsPerChunk, [&](std::size_t jBegin, std::size_t jEnd) {
        std::vector<const float*> at(n), end(n);
        std::vector<std::uint8_t> odd(n);
        for (std::size_t j = jBegin; j < jEnd; ++j) {
            for (std::uint32_t i = 0; i < n; ++i) {
                const glm::vec3 t = g.toTexture(cells.centre(i, std::uint32_t(j), k0));
                const float fs = std::floor(t.x * float(g.width));
                const float ft = std::floor(t.y * float(g.height));
                at[i] = end[i] = nullptr;
                odd[i] = 0;
                if (fs >= 0.0f && fs < float(g.width) && ft >= 0.0f && ft < float(g.height)) {
                    const std::size_t c = std::size_t(ft) * g.width + std::size_t(fs);
                    at[i] = crossings + offsets[c];
                    end[i] = crossings + offsets[c + 1];
                }
            }
            for (std::uint32_t k = k0; k < k1; ++k) {
                const float r = depth[k - k0];
                std::uint8_t* out = labels + (k - k0) * layer + j * n;
                if (!(r >= 0.0f && r <= 1.0f)) {
                    std::memset(out, 0, n);
                    continue;
                }
                for (std::uint32_t i = 0; i < n; ++i) {
                    const float* e = at[i];
                    std::uint8_t parity = odd[i];
                    for (; e != end[i] && std::fabs(*e) < r; ++e) parity ^= 1;
                    at[i] = e;
                    odd[i] = parity;
                    out[i] = parity;
                }
            }
        }
    });
}

} // namespace vds::peers
