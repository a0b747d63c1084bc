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
    const glm::vec3 d(p.x - box.lo.x, p.y - box.lo.y, p.z - box.lo.z);
    return {d.x * scale.x, d.y * scale.y, d.z * scale.z};
}

bool VoxelGrid::cellOf(const glm::vec3& p, glm::uvec3& cell) const {
    const glm::vec3 v = toCells(p);
    const float f[3] = {std::floor(v.x), std::floor(v.y), std::floor(v.z)};
    for (int a = 0; a < 3; ++a)
        if (!(f[a] >= 0.0f && f[a] < float(dims[a]))) return false;
    cell = glm::uvec3(std::uint32_t(f[0]), std::uint32_t(f[1]), std::uint32_t(f[2]));
    return true;
}

float VoxelGrid::cellSize() const { return float(1.0 / double(scale.x)); }

VoxelGrid makeVoxelGrid(const Box& box, std::uint32_t resolution) {
    if (resolution == 0 || resolution > kMaxResolution)
        throw InvalidArgument("resolution " + std::to_string(resolution) + " is out of range (1 to " +
                              std::to_string(kMaxResolution) + ")");
    const glm::vec3 ext = box.hi - box.lo;
    static const char* const names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a])) throw InvalidArgument("box is not finite");
        if (!(ext[a] > 0.0f)) throw InvalidArgument(std::string("box has no extent along ") + names[a]);
    }
    VoxelGrid g;
    static_cast<Grid&>(g) = cubicGrid(box, resolution);
    const double longest = std::max({double(ext.x), double(ext.y), double(ext.z)});
    g.scale = glm::vec3(float(resolution / longest));
    return g;
}

VoxelGrid makeSlicemapGrid(const Box& box, std::uint32_t resolution, std::uint32_t slices) {
    return slicemapGridOver(makeVoxelGrid(box, resolution), box, slices);
}

VoxelGrid slicemapGridOver(const VoxelGrid& columns, const Box& box, std::uint32_t slices) {
    VoxelGrid g = columns;
    g.dims.z = slices;
    g.box.hi.z = box.hi.z;
    g.scale.z = float(double(slices) / (double(box.hi.z) - double(box.lo.z)));
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
    checkGrid(grid); // at most kMaxGridCells cells, as every grid the library fills
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
