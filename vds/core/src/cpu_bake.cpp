// vds: the CPU baker. Trapp & Döllner 2008, section 4.1 (the LDI: every
// crossing of every texel's ray), by exact ray casting at the texel centres
// with the classifier's predicates and tie rule (projected_mesh.h).
#include <vds/bake.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <thread>

#include <vds/error.h>
#include <vds/detail/parallel.h>

#include <vds/detail/bake_common.h>
#include "projected_mesh.h"

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

} // namespace

Sprite bakeCpu(MeshView mesh, const BakeOptions& options) {
    const detail::BakeClock clock(options.timings);
    const detail::BakeSetup setup = detail::prepareBake(mesh, options);
    const SpriteGrid& grid = setup.grid;
    const auto report = [&](const std::string& message) {
        if (options.progress) options.progress(message);
    };
    report("cpu bake: indexing " + std::to_string(mesh.triangleCount) + " triangles");
    std::optional<detail::HostPhase> phase(std::in_place, options.timings, BakePhase::Upload);
    const ProjectedMesh projected(mesh, grid.axis);

    // Texture-space depth of every vertex, as the GL bakers' vertex stage computes it.
    std::vector<std::array<float, 3>> vertexDepth(projected.crossable);
    for (std::size_t k = 0; k < projected.crossable; ++k)
        for (int c = 0; c < 3; ++c) {
            glm::vec3 world;
            for (int a = 0; a < 3; ++a) world[projected.perm[a]] = projected.tris[k].v[c][a];
            vertexDepth[k][std::size_t(c)] = grid.toTexture(world).z;
        }
    phase.emplace(options.timings, BakePhase::Raster);

    const std::uint32_t width = grid.width, height = grid.height;
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    report("cpu bake: casting " + std::to_string(width) + "x" + std::to_string(height) + " rays on " +
           std::to_string(threads) + " threads");
    std::vector<std::uint32_t> offsets(std::size_t(width) * height + 1, 0);
    std::vector<std::vector<float>> rows(height);
    parallelFor(threads, height, 1, [&](std::size_t row, std::size_t) {
        std::vector<Crossing> column;
        std::vector<float>& out = rows[row];
        for (std::uint32_t i = 0; i < width; ++i) {
            float q[3];
            projected.toViewSpace(grid.texelCentre(i, std::uint32_t(row), 0.0f), q);
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
            offsets[row * width + i + 1] = std::uint32_t(column.size());
        }
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
