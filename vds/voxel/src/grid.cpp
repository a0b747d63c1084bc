#include <vds/voxel/grid.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <new>
#include <string>

#include <vds/error.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>

namespace vds::voxel {

float snapToSubcells(float v) { return std::floor(v * kSubcells + 0.5f) / kSubcells; }

glm::vec3 VoxelGrid::toCells(const glm::vec3& p) const {
    const glm::vec3 d(p.x - origin.x, p.y - origin.y, p.z - origin.z);
    return {d.x * scale.x, d.y * scale.y, d.z * scale.z};
}

bool VoxelGrid::cellOf(const glm::vec3& p, glm::uvec3& cell) const {
    const glm::vec3 v = toCells(p);
    const float f[3] = {std::floor(v.x), std::floor(v.y), std::floor(v.z)};
    for (int a = 0; a < 3; ++a)
        if (!(f[a] >= 0.0f && f[a] < float(size[a]))) return false;
    cell = glm::uvec3(std::uint32_t(f[0]), std::uint32_t(f[1]), std::uint32_t(f[2]));
    return true;
}

glm::vec3 VoxelGrid::cellCentre(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    return {origin.x + (float(i) + 0.5f) * cellSize, origin.y + (float(j) + 0.5f) * cellSize,
            origin.z + (float(k) + 0.5f) * cellSize};
}

Box VoxelGrid::box() const {
    Box b;
    b.lo = origin;
    for (int a = 0; a < 3; ++a) b.hi[a] = origin[a] + float(size[a]) / scale[a];
    return b;
}

VoxelGrid makeVoxelGrid(const Box& box, std::uint32_t resolution, std::uint64_t maxCells) {
    if (resolution == 0 || resolution > kMaxResolution)
        throw InvalidArgument("resolution " + std::to_string(resolution) + " is out of range (1 to " +
                              std::to_string(kMaxResolution) + ")");
    const glm::vec3 ext = box.hi - box.lo;
    static const char* const names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a])) throw InvalidArgument("box is not finite");
        if (!(ext[a] > 0.0f)) throw InvalidArgument(std::string("box has no extent along ") + names[a]);
    }
    const double longest = std::max({double(ext.x), double(ext.y), double(ext.z)});
    const double cell = longest / resolution;
    VoxelGrid g;
    g.origin = box.lo;
    g.cellSize = float(cell);
    g.scale = glm::vec3(float(resolution / longest));
    g.size = cubicCells(ext, resolution);
    if (std::uint64_t(g.size.x) * g.size.y * g.size.z > maxCells)
        throw InvalidArgument("a " + std::to_string(g.size.x) + "x" + std::to_string(g.size.y) + "x" +
                              std::to_string(g.size.z) + " voxel grid has more than " + std::to_string(maxCells) +
                              " cells; lower the resolution");
    return g;
}

void BitGrid::set(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool on) {
    std::uint32_t& w = words[wordIndex(grid, x, y, z)];
    const std::uint32_t bit = 1u << (z & 31u);
    w = on ? (w | bit) : (w & ~bit);
}

bool BitGrid::contains(const glm::vec3& p) const {
    glm::uvec3 c;
    return grid.cellOf(p, c) && test(c.x, c.y, c.z);
}

std::size_t BitGrid::count() const {
    std::size_t n = 0;
    for (std::uint32_t w : words) n += std::bitset<32>(w).count();
    return n;
}

BitGrid makeBitGrid(const VoxelGrid& grid) {
    BitGrid b;
    b.grid = grid;
    try {
        b.words.assign(grid.wordCount(), 0u);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory("cannot allocate a voxel grid of " + std::to_string(grid.wordCount() * 4) + " bytes");
    }
    return b;
}

void requireClosed(MeshView mesh, const char* what) {
    // Every voxelizer here decides inside by parity (XOR of crossings).
    requireInsideDefined(validateMesh(mesh), what, Rule::Parity);
}

} // namespace vds::voxel
