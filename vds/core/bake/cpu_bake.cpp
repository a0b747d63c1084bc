// vds: the CPU baker. Trapp & Döllner 2008, section 4.1 (the LDI: every
// crossing of every texel's ray), by exact ray casting at the texel centres
// with the classifier's predicates and tie rule (projected_mesh.h).
#include <vds/bake.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <thread>

#include <vds/error.h>
#include <vds/detail/parallel.h>

#include <vds/detail/bake_common.h>
#include <vds/detail/projected_mesh.h>

namespace vds {

using detail::CellEntry;
using detail::CellGrid;
using detail::ProjectedMesh;
using detail::Triangle;

namespace {

struct Crossing {
    float depth;
    std::uint32_t triangle;
    bool entering;
};

/// Depth of the plane of `tri` at q, in LDI texture space: the barycentric
/// coordinates of q in (s,t) (invariant under the grid's affine map) weight
/// the vertices' texture depths `r`. q is in the closed triangle, so the
/// result is kept within the vertices' depth range despite rounding.
float planeDepth(const Triangle& tri, const float* q, const std::array<float, 3>& r) {
    double weight[3], total = 0.0;
    for (int k = 0; k < 3; ++k) {
        const float* a = tri.v[(k + 1) % 3];
        const float* b = tri.v[(k + 2) % 3];
        const double w = (double(b[0]) - a[0]) * (double(q[1]) - a[1]) - (double(b[1]) - a[1]) * (double(q[0]) - a[0]);
        weight[k] = std::max(w, 0.0);
        total += weight[k];
    }
    double depth = total > 0.0 ? (weight[0] * r[0] + weight[1] * r[1] + weight[2] * r[2]) / total
                               : (double(r[0]) + r[1] + r[2]) / 3.0;
    depth = std::clamp(depth, double(std::min({r[0], r[1], r[2]})), double(std::max({r[0], r[1], r[2]})));
    return std::clamp(float(depth), 0.0f, 1.0f);
}

/// Exact crossings of texel columns: the mesh indexed once, then any column
/// cast on its own (thread safe).
struct ColumnCaster {
    ColumnCaster(MeshView mesh, const SpriteGrid& spriteGrid) : grid(spriteGrid), projected(mesh, spriteGrid.axis) {
        // Texture-space depth of every vertex, as the GL bakers' vertex stage computes it.
        vertexDepth.resize(projected.crossable);
        for (std::size_t k = 0; k < projected.crossable; ++k)
            for (int c = 0; c < 3; ++c) {
                glm::vec3 world;
                for (int a = 0; a < 3; ++a) world[projected.perm[a]] = projected.tris[k].v[c][a];
                vertexDepth[k][std::size_t(c)] = grid.toTexture(world).z;
            }
    }
    /// Appends column (i, j)'s encoded crossings to `out`, sorted by depth
    /// (ties by triangle index); returns how many. `column` is scratch.
    std::uint32_t cast(std::uint32_t i, std::uint32_t j, std::vector<Crossing>& column, std::vector<float>& out) const {
        float q[3];
        projected.toViewSpace(grid.texelCentre(i, j, 0.0f), q);
        column.clear();
        const CellGrid::Found found = projected.grid.find(q);
        for (const CellEntry* e = found.begin; e != found.end; ++e) {
            if (!CellGrid::mayHold(*e, found.sub)) continue;
            const Triangle& t = projected.tris[e->triangle];
            if (detail::claims(t, q))
                column.push_back({planeDepth(t, q, vertexDepth[e->triangle]), t.index, (t.flags & detail::kEntering) != 0});
        }
        std::sort(column.begin(), column.end(), [](const Crossing& a, const Crossing& b) {
            return a.depth < b.depth || (a.depth == b.depth && a.triangle < b.triangle);
        });
        for (const Crossing& c : column) out.push_back(encodeCrossing(c.depth, c.entering));
        return std::uint32_t(column.size());
    }

    const SpriteGrid& grid;
    ProjectedMesh projected;
    std::vector<std::array<float, 3>> vertexDepth;
};

} // namespace

void detail::recastBoundaryColumns(MeshView mesh, const SpriteGrid& grid, const std::vector<glm::vec3>& edges,
                                   std::vector<std::uint32_t>& offsets, std::vector<float>& crossings) {
    if (edges.empty()) return;
    const std::uint32_t width = grid.width, height = grid.height;
    // Texels whose centre lies within about a texel of a boundary edge's
    // projection: walk each edge in half-texel steps, marking the 3 x 3
    // texels around each step's nearest centre.
    std::vector<std::uint8_t> near(std::size_t(width) * height, 0);
    for (std::size_t k = 0; k + 1 < edges.size(); k += 2) {
        const glm::vec3 a = grid.toTexture(edges[k]), b = grid.toTexture(edges[k + 1]);
        const glm::dvec2 ta(double(a.x) * width - 0.5, double(a.y) * height - 0.5),
            tb(double(b.x) * width - 0.5, double(b.y) * height - 0.5);
        const double length = std::max(std::fabs(tb.x - ta.x), std::fabs(tb.y - ta.y));
        const auto steps = std::size_t(std::ceil(2.0 * length)) + 1;
        for (std::size_t n = 0; n <= steps; ++n) {
            const glm::dvec2 at = ta + (tb - ta) * (double(n) / double(steps));
            const double ci = std::round(at.x), cj = std::round(at.y);
            for (double dj = -1; dj <= 1; ++dj)
                for (double di = -1; di <= 1; ++di) {
                    const double i = ci + di, j = cj + dj;
                    if (i < 0 || j < 0 || i >= double(width) || j >= double(height)) continue;
                    near[std::size_t(j) * width + std::size_t(i)] = 1;
                }
        }
    }
    const ColumnCaster caster(mesh, grid);
    std::vector<std::uint32_t> newOffsets(offsets.size(), 0);
    std::vector<float> out;
    out.reserve(crossings.size());
    std::vector<Crossing> scratch;
    for (std::uint32_t j = 0; j < height; ++j)
        for (std::uint32_t i = 0; i < width; ++i) {
            const std::size_t c = std::size_t(j) * width + i;
            if (near[c]) {
                caster.cast(i, j, scratch, out);
            } else {
                out.insert(out.end(), crossings.begin() + std::ptrdiff_t(offsets[c]),
                           crossings.begin() + std::ptrdiff_t(offsets[c + 1]));
            }
            if (out.size() > std::numeric_limits<std::uint32_t>::max())
                throw OutOfMemory("bake: more crossings than the sprite's 2^32 - 1 limit");
            newOffsets[c + 1] = std::uint32_t(out.size());
        }
    offsets = std::move(newOffsets);
    crossings = std::move(out);
}

Sprite bakeCpu(MeshView mesh, const BakeOptions& options) {
    const detail::BakeClock clock(options.timings);
    return detail::bakeCpu(detail::prepareBake(mesh, options), mesh, options);
}

Sprite detail::bakeCpu(const BakeSetup& setup, MeshView mesh, const BakeOptions& options) {
    const SpriteGrid& grid = setup.grid;
    const auto report = [&](const std::string& message) {
        if (options.progress) options.progress(message);
    };
    report("cpu bake: indexing " + std::to_string(mesh.triangleCount) + " triangles");
    std::optional<detail::HostPhase> phase(std::in_place, options.timings, BakePhase::Upload);
    const ColumnCaster caster(mesh, grid);
    phase.emplace(options.timings, BakePhase::Raster);

    const std::uint32_t width = grid.width, height = grid.height;
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    report("cpu bake: casting " + std::to_string(width) + "x" + std::to_string(height) + " rays on " +
           std::to_string(threads) + " threads");
    std::vector<std::uint32_t> offsets(std::size_t(width) * height + 1, 0);
    std::vector<std::vector<float>> rows(height);
    detail::parallelFor(threads, height, 1, [&](std::size_t row, std::size_t) {
        std::vector<Crossing> column;
        for (std::uint32_t i = 0; i < width; ++i)
            offsets[row * width + i + 1] = caster.cast(i, std::uint32_t(row), column, rows[row]);
    });

    phase.emplace(options.timings, BakePhase::Scan); // the column offsets and the rows joined
    std::uint64_t total = 0;
    for (const auto& r : rows) total += r.size();
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw OutOfMemory("cpu bake: " + std::to_string(total) + " crossings exceed the sprite's 2^32 - 1 limit");
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    std::vector<float> crossings;
    crossings.reserve(std::size_t(total));
    for (auto& r : rows) {
        crossings.insert(crossings.end(), r.begin(), r.end());
        std::vector<float>().swap(r);
    }
    phase.reset();
    report("cpu bake: " + std::to_string(total) + " crossings");
    return detail::assembleSprite(setup, options, mesh, std::move(offsets), std::move(crossings));
}

} // namespace vds
