// vds::voxel: geometry-shader slicing voxelization (Chang, Lai, Yao, Hua,
// Niu, Liu, "Geometry-shader-based real-time voxelization and applications",
// The Visual Computer 30, 2014, section 3 and figure 2).
//
// One pass: a geometry shader duplicates each triangle into every z slice of
// cells its depth range spans, sets the slice as gl_Layer of a layered 3D
// texture framebuffer and clips the copy to the slice's slab [k, k+1] (cell
// units) with two clip distances; the rasterizer then covers the columns
// whose centres the clipped piece covers. Each fragment adds (its triangle's
// unit normal, 1) to its voxel by additive blending into an RGBA32F texel, so
// a voxel ends up with its fragment count (the paper's absorption
// coefficient is that count times a per-fragment constant, section 4) and the
// sum of its normals (averaged: the normal stored for refraction, section 5).
//
// Like any rasterization it is not conservative: a surface nearly parallel
// to z yields thin slivers per slab that may cover no column centre, and
// surfaces exactly parallel to z none at all (holes, the paper's figure 6b;
// `slabPadding` widens the slabs as the paper's "extension" heuristic does).
// A piece on a slab boundary belongs to both slabs.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/voxel/grid.h>

namespace vds::voxel {

struct SlicingOptions {
    /// Absorption added per fragment (the paper's user-specified constant).
    float absorptionPerFragment = 1.0f;
    /// Widening of each slab on both sides, in cells (0: exact slabs).
    float slabPadding = 0.0f;
};

/// Per-voxel properties in host memory.
struct SlicedVoxels {
    VoxelGrid grid;
    /// (sum of unit normals, fragment count) per voxel, 3D texture order:
    /// index (z * size.y + y) * size.x + x.
    std::vector<glm::vec4> voxels;
    float absorptionPerFragment = 1.0f;
    /// Instances of the one draw call: each geometry invocation emits at most
    /// a chunk of slices (its output limit), the instance picks the chunk.
    std::uint32_t instances = 0;

    std::size_t index(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return (std::size_t(z) * grid.dims.y + y) * grid.dims.x + x;
    }
    std::uint32_t fragments(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return std::uint32_t(voxels[index(x, y, z)].w);
    }
    /// Absorption coefficient: fragments * absorptionPerFragment.
    float absorption(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return voxels[index(x, y, z)].w * absorptionPerFragment;
    }
    /// Averaged normal (unit length), or 0 for an empty voxel or cancelling normals.
    glm::vec3 normal(std::uint32_t x, std::uint32_t y, std::uint32_t z) const;
    /// Occupancy as a bit grid (voxels with at least one fragment).
    BitGrid occupancy() const;
    /// Bytes of the RGBA32F texture.
    std::size_t memoryBytes() const { return voxels.size() * sizeof(glm::vec4); }
};

/// Voxelizes the surface of `mesh` on `grid` (open meshes are fine). Throws
/// `InvalidMesh` for an unusable mesh, `InvalidArgument` if the grid exceeds
/// GL's 3D texture size, `OutOfMemory` if the texture exceeds 2 GiB or GL
/// cannot hold it,
/// `GlError` on GL failure.
SlicedVoxels voxelizeSlices(const GlContext& gl, MeshView mesh, const VoxelGrid& grid,
                            const SlicingOptions& options = {});

} // namespace vds::voxel
