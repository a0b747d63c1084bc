// vds::voxel: light transmittance through semi-transparent casters, from a
// slicemap, a per-voxel absorption grid or a volumetric depth sprite, each
// built along the light, and exact CPU references for all of them.
//
//  - Transmittance shadow maps (Eisemann & Décoret, "Fast Scene Voxelization
//    and Applications", I3D 2006, section 3.1): every surface in front of a
//    receiver attenuates the light by sigma; the slices of the slicemap in
//    front of the receiver's slice that are occupied (the summask: popcount of
//    the column's bit words up to that slice) count the surfaces n, and the
//    light left is (1 - sigma)^n. Front and back slicemaps are counted
//    separately, so a closed solid crossed once counts 2.
//  - Transparent shadows with per-voxel absorption (Chang et al., "Geometry-
//    shader-based real-time voxelization and applications", The Visual
//    Computer 2014, section 4, equation 1): the absorption of the voxels of
//    the column in front of the receiver (fragment count times a constant)
//    is summed to A; the light left is exp(-A).
//  - Optical path length from a VDS (this project's addition): a sprite
//    baked along the light stores each column's exact entry and exit depths,
//    so the length t of the light ray inside the solid in front of the
//    receiver is the sum of its (exit - entry) intervals clipped at the
//    receiver; the light left is exp(-extinction * t) (Beer-Lambert).
//
// The light is directional. Every representation is built from the casters
// in *light space*, where the light travels along +z (`LightFrame`): the
// slicemap's slices, the voxel grid's z and the sprite's Axis::Z then all
// run along the light, and "in front of a receiver" is "lower light-space z
// in the same column". Receivers are given in world coordinates.
//
// Columns are sampled at their centres (slicemap, voxels, sprite alike), so
// all three are exact only to a column across the light; along it the
// slicemap and the voxels are exact to a slice, the sprite to float rounding.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/sprite.h>
#include <vds/mesh.h>
#include <vds/sprite.h>
#include <vds/voxel/caster.h>
#include <vds/voxel/light_frame.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/slicing.h>

namespace vds::voxel {

/// How the light left at a receiver is computed.
enum class TransmittanceSource : std::uint8_t {
    SlicemapSurfaces, ///< (1 - sigma)^n, n occupied front and back slices in front (E&D 2006)
    VoxelAbsorption,  ///< exp(-A), A the summed per-voxel absorption in front (Chang et al. 2014)
    SpriteThickness,  ///< exp(-extinction * t), t the path length inside the solid in front (a VDS)
};

struct TransmittanceParameters {
    float sigma = 0.3f;      ///< attenuation per surface, in [0, 1] (slicemap)
    float extinction = 1.0f; ///< per mesh unit of path inside the solid (sprite), >= 0
};

// ---- CPU references. Points are in light space (`LightFrame::toLightSpace`).

/// Occupied slices of `map`'s front map plus those of its back map in the
/// column of `p`, strictly in front of the slice of `p` (the receiver's own
/// slice is left out: no self-shadowing). Beyond the far end of the column
/// (uniform: the box; local: the column's far depth) every slice counts; in
/// front of it, or outside the columns, none. (`buildSlicemap` takes closed
/// meshes only: open surfaces such as leaves go in double-sided, and then
/// each counts 2, once per map.)
std::uint32_t slicemapSurfacesInFront(const Slicemap& map, const glm::vec3& p);

/// Summed absorption (`SlicedVoxels::absorption`) of the voxels of the column
/// of `p` strictly in front of the voxel holding `p`; beyond the grid the
/// whole column; in front of the grid or outside its columns 0.
float absorptionInFront(const SlicedVoxels& voxels, const glm::vec3& p);

/// Length, in mesh units, of the part of the ray from the sprite's near side
/// to `p` along its axis, through the centre of `p`'s texel column, that lies
/// inside the solid (non-zero winding); points past the far side count the
/// whole column. `sprite` must have been baked with Axis::Z. Same arithmetic
/// as `vdsSpriteThicknessInFront` in shaders/voxel/transmittance.glsl.
float spriteThicknessInFront(const Sprite& sprite, const glm::vec3& p);

/// The exact answers for a closed light-space mesh, by intersecting the ray
/// through `p` itself (not a column centre) along +z with every triangle in
/// double precision: the surfaces crossed strictly in front of p, and the
/// length inside the solid (non-zero winding) in front of it. O(triangles).
struct ExactCrossings {
    std::uint32_t surfaces = 0;
    double thickness = 0.0;
};
ExactCrossings exactCrossingsInFront(MeshView lightSpaceMesh, const glm::vec3& p);

/// The light left for a quantity of `source` (surfaces n, absorption A or
/// thickness t): (1 - sigma)^n, exp(-A) or exp(-extinction * t).
float transmittanceOf(TransmittanceSource source, double quantity, const TransmittanceParameters& parameters);

// ---- Receivers and images.

/// A rectangle of receivers in world coordinates, sampled at pixel centres:
/// pixel (i, j), i < width, j < height, is the point origin + ((i + 0.5) /
/// width) * u + ((j + 0.5) / height) * v. Row j = 0 is the GL's bottom row.
struct ReceiverPlane {
    glm::vec3 origin{0.0f};
    glm::vec3 u{1.0f, 0.0f, 0.0f};
    glm::vec3 v{0.0f, 1.0f, 0.0f};
    std::uint32_t width = 64, height = 64;

    /// The receiver at pixel (i, j), in the order of arithmetic of the GLSL.
    glm::vec3 point(std::uint32_t i, std::uint32_t j) const;
};

/// Per pixel of a receiver plane, row-major from the bottom row: the
/// quantity (surfaces, absorption or thickness) and the light left.
struct TransmittanceImage {
    std::uint32_t width = 0, height = 0;
    std::vector<float> quantity;
    std::vector<float> transmittance;
    double gpuMilliseconds = 0.0;  ///< GL_TIME_ELAPSED of the draw (0 for CPU images)
    /// Wall time from issuing the draw to glFinish's return (0 for CPU
    /// images). On a deferred software rasterizer such as llvmpipe the
    /// fragments are shaded at the flush, which GL_TIME_ELAPSED may not see:
    /// there this is the figure to quote.
    double wallMilliseconds = 0.0;
};

/// CPU image: `quantityAt(lightSpacePoint)` per pixel, and its transmittance.
/// Rows run on every hardware thread: `quantityAt` is called concurrently
/// and must be thread safe (the references above are: they only read).
/// The references above fit in: e.g. [&](glm::vec3 p) { return
/// double(slicemapSurfacesInFront(map, p)); }.
TransmittanceImage transmittanceOnCpu(const ReceiverPlane& plane, const LightFrame& frame,
                                      TransmittanceSource source, const TransmittanceParameters& parameters,
                                      const std::function<double(const glm::vec3&)>& quantityAt);

/// One caster representation on the GPU, for `renderTransmittance` and for
/// the samplers of shaders/voxel/transmittance.glsl. Move-only; belongs to
/// the context (and thread) it was made in: the constructors taking a
/// `GlContext` make it current for the call, the others use the current
/// one (of any origin). `render*` refuses a caster of another context.
class GpuTransmittanceCaster : public GpuCaster {
public:
    /// Uploads a slicemap pair (uniform or local): RGBA32UI array texture,
    /// plus an RGBA32F range texture for local slicing.
    explicit GpuTransmittanceCaster(const Slicemap& map);
    /// Uploads per-voxel absorption: an R32F 3D texture of absorption.
    explicit GpuTransmittanceCaster(const SlicedVoxels& voxels);
    /// Uploads a sprite baked along Axis::Z (throws `InvalidArgument` for
    /// another axis): its LDI texture, as `GpuSprite` does.
    explicit GpuTransmittanceCaster(const Sprite& sprite);
    /// The same, on `gl` (made current for the call, the caller's restored).
    GpuTransmittanceCaster(const GlContext& gl, const Slicemap& map);
    GpuTransmittanceCaster(const GlContext& gl, const SlicedVoxels& voxels);
    GpuTransmittanceCaster(const GlContext& gl, const Sprite& sprite);

    TransmittanceSource source() const { return source_; }
    /// A slicemap with local slicing (the shader then reads the ranges too).
    bool isLocal() const { return local_; }
    /// Binds the textures to units 0 (and 1) and sets the uniforms that
    /// shaders/voxel/transmittance_plane.frag declares for this source in
    /// `program` (in use).
    void setUniforms(GLuint program) const;

private:
    TransmittanceSource source_;
    bool local_ = false;
    float depthExtent_ = 0.0f;
};

/// Renders the receiver plane into an RG32F target (quantity, light left)
/// with one full-screen draw of shaders/voxel/transmittance_plane.frag and
/// reads it back; times the draw with a GL_TIME_ELAPSED query (after an
/// untimed first draw, which may include the driver's shader compilation). Throws
/// `InvalidArgument` for an empty or oversized plane, `GlError` on GL failure.
TransmittanceImage renderTransmittance(const GlContext& gl, const GpuTransmittanceCaster& caster,
                                       const LightFrame& frame, const ReceiverPlane& plane,
                                       const TransmittanceParameters& parameters);

} // namespace vds::voxel
