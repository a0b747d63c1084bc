// vds::voxel: refraction through closed solids seen in front of a
// checkerboard, from the representations of this module and a VDS, with an
// exact CPU reference by ray-mesh intersection.
//
//  - Two-surface refraction (Eisemann & Décoret, "Fast Scene Voxelization
//    and Applications", I3D 2006, section 3.3, after Wyman 2005; Chang et
//    al. 2014, section 5.1): the eye ray enters at the front surface and is
//    refracted there; the length d it travels inside is taken from the
//    straight eye ray (the sum of its inside intervals); it leaves at
//    P2 = P1 + d T1 and is refracted by the back surface there. From a local
//    slicemap pair (E&D: front depth = the column's near depth, back = far,
//    d = inner voxels times the slice length), or from a VDS baked along the
//    view (entry and exit depths and d exact per column). Neither stores
//    normals: they come from the depth differences of neighbouring columns.
//  - Multiple-surface refraction by marching voxels (Chang et al. 2014,
//    section 5.2): the ray steps through the geometry-shader voxelization
//    (<vds/voxel/slicing.h>), half a cell at a time, and is refracted by the
//    averaged normal of every boundary voxel where it enters (outside, the
//    normal facing it) or leaves (inside, the normal facing away); total
//    internal reflection reflects it.
//  - Frosted glass (E&D 2006, section 3.3): the background is blurred by a
//    box filter whose width grows with the length travelled inside.
//
// Everything is in *view space*: the camera is orthographic and looks along
// +z (make the frame with `makeLightFrame(viewDirection)` and the view-space
// mesh with `toLightSpace`), so every representation is built along the view.
// The background is the plane z = `RefractionView::backgroundZ` with a
// checkerboard; a ray that leaves the solids travelling away from it sees
// black.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/sprite.h>
#include <vds/mesh.h>
#include <vds/sprite.h>
#include <vds/voxel/caster.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/slicing.h>

namespace vds::voxel {

enum class RefractionMethod : std::uint8_t {
    SlicemapTwoSurface, ///< local slicemap pair (E&D 2006)
    SpriteTwoSurface,   ///< VDS baked along the view (Axis::Z)
    VoxelMarch,         ///< per-voxel normals, refracted at every boundary (Chang et al. 2014)
    Exact,              ///< CPU only: ray-mesh intersection with the triangles' normals, every surface
};

/// The rays: pixel (i, j) starts at view-space (x, y, startZ), x, y =
/// lo + (hi - lo) * ((i + 0.5) / width, (j + 0.5) / height), along +z.
/// Row j = 0 is the bottom row.
struct RefractionView {
    glm::vec2 lo{0.0f}, hi{1.0f};
    std::uint32_t width = 64, height = 64;
    float startZ = 0.0f;      ///< in front of every solid
    float backgroundZ = 1.0f; ///< the checkerboard plane, behind every solid

    glm::vec2 rayXY(std::uint32_t i, std::uint32_t j) const;
};

struct RefractionParameters {
    float eta = 1.33f;        ///< refractive index of the solids (outside: 1)
    float absorption = 0.8f;  ///< per unit of length inside; red absorbs this, green 0.35x, blue 0.2x
    float frost = 0.0f;       ///< blur width on the background per unit of length inside (0: clear glass)
    float checker = 0.25f;    ///< checkerboard square size, view-space units
    std::uint32_t maxSteps = 4096; ///< voxel march limit (half-cell steps)
    std::uint32_t maxBounces = 16; ///< exact tracer limit (surfaces crossed or reflected at)
};

/// Per pixel, row-major from the bottom row.
struct RefractionImage {
    std::uint32_t width = 0, height = 0;
    /// (x, y) where the ray meets the background plane, the length it
    /// travelled inside the solids, and 1 if it met the background (0: it
    /// left travelling away, or the march or bounce limit ran out).
    std::vector<glm::vec4> hits;
    std::vector<std::uint8_t> rgba; ///< shaded colour, 4 bytes a pixel
    double gpuMilliseconds = 0.0;   ///< GL_TIME_ELAPSED of the draw (0 on the CPU)
    double wallMilliseconds = 0.0;  ///< draw to glFinish (0 on the CPU); the figure to quote on llvmpipe
};

/// The colour of a ray meeting the background at `hit` (RefractionImage::hits),
/// as shaders/voxel/refraction.glsl computes it: the checkerboard, box-
/// filtered over frost * length, times exp(-absorption * length * (1, 0.35, 0.2)).
glm::vec3 refractionColour(const glm::vec4& hit, const RefractionParameters& parameters);

// ---- CPU references (view space). Rows run on every hardware thread; the
// inputs are only read.

/// Two-surface refraction from a local slicemap pair (throws
/// `InvalidArgument` for uniform slicing), a sprite baked along Axis::Z, or
/// voxel marching; the same arithmetic as the GLSL, in float.
RefractionImage refractOnCpu(const Slicemap& map, const RefractionView& view, const RefractionParameters& parameters);
RefractionImage refractOnCpu(const Sprite& sprite, const RefractionView& view, const RefractionParameters& parameters);
RefractionImage refractOnCpu(const SlicedVoxels& voxels, const RefractionView& view,
                             const RefractionParameters& parameters);
/// The exact reference: every ray traced through the view-space mesh by
/// ray-triangle intersection in double, refracted (or totally reflected) at
/// every surface it meets with that triangle's normal. O(triangles) a bounce.
RefractionImage refractExactly(MeshView viewSpaceMesh, const RefractionView& view,
                               const RefractionParameters& parameters);

/// A representation on the GPU for `renderRefraction`. Move-only; belongs to
/// the context (and thread) it was made in: the constructors taking a
/// `GlContext` make it current for the call, the others use the current
/// one (of any origin). `render*` refuses a caster of another context.
class GpuRefractionCaster : public GpuCaster {
public:
    explicit GpuRefractionCaster(const Slicemap& map); ///< local slicing only (`InvalidArgument`)
    explicit GpuRefractionCaster(const Sprite& sprite); ///< Axis::Z only (`InvalidArgument`)
    explicit GpuRefractionCaster(const SlicedVoxels& voxels);
    /// The same, on `gl` (made current for the call, the caller's restored).
    GpuRefractionCaster(const GlContext& gl, const Slicemap& map);
    GpuRefractionCaster(const GlContext& gl, const Sprite& sprite);
    GpuRefractionCaster(const GlContext& gl, const SlicedVoxels& voxels);

    RefractionMethod method() const { return method_; }
    /// Binds textures to units 0 and 1 and sets the uniforms
    /// shaders/voxel/refraction.frag declares for this method in `program` (in use).
    void setUniforms(GLuint program) const;

private:
    RefractionMethod method_;
    float depthLo_ = 0.0f, depthExtent_ = 0.0f, columnStep_ = 0.0f;
};

/// Renders the rays of `view` with one full-screen draw into an RGBA32F
/// target (the hits) and an RGBA8 one (the colours), reads both back, and
/// times the draw (after an untimed first draw). Throws `InvalidArgument` for
/// an empty or oversized view, `GlError` on GL failure.
RefractionImage renderRefraction(const GlContext& gl, const GpuRefractionCaster& caster, const RefractionView& view,
                                 const RefractionParameters& parameters);

} // namespace vds::voxel
