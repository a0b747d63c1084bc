// vds: the umbrella (vds::vds) — every layer's headers, and the entry points
// that reach every method: `makeClassifier` builds any `Method` of
// <vds/classify.h> from a mesh or a sprite, `bake` bakes by any
// `BakeMethod`. Link vds::vds (core, gl and voxel) to use them.
//
// GL: the forms that take a `const GlContext&` first use that context (made
// current for each call; the caller's is current again afterwards; it must
// outlive the classifier). The forms without one make a private headless
// context when the method needs GL, owned by the classifier (or the call).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <vds/bake.h>
#include <vds/certified.h>
#include <vds/classify.h>
#include <vds/exact.h>
#include <vds/gl/bake.h>
#include <vds/gl/certified.h>
#include <vds/gl/classifier.h>
#include <vds/gl/context.h>
#include <vds/gl/sprite.h>
#include <vds/mesh.h>
#include <vds/mesh_io.h>
#include <vds/occupancy.h>
#include <vds/sprite.h>
#include <vds/vds.h>
#include <vds/voxel/representation.h>

namespace vds {

/// How `makeClassifier` builds a method from a mesh.
struct MethodOptions {
    /// Texels (sprites, certified bands) or cells (voxel representations) on
    /// the box's longest side; 0: the method's `MethodInfo::defaultResolution`.
    std::uint32_t resolution = 0;
    /// Sprites: the view axis, unset (the default) for the one with the fewest
    /// layers at `resolution` (`chooseViewAxis`); certified bands and the exact
    /// classifier: their axis, unset for z.
    std::optional<Axis> axis;
    BakeMethod bakeMethod = BakeMethod::Cpu; ///< how sprite methods bake (the CPU baker needs no GL)
    std::uint32_t slices = 0;               ///< slicemaps: 0 = the box depth in cells
    unsigned threads = 0;                   ///< for building; 0: one per hardware thread
    std::string sourceName;                 ///< recorded in a baked sprite
};

/// Builds `method` for `mesh` (mesh coordinates). Throws `InvalidMesh` for an
/// unusable mesh (and an open one for the voxel representations),
/// `InvalidArgument` for options out of range, `GlUnavailable` when a GL
/// method finds no GL.
std::unique_ptr<Classifier> makeClassifier(MeshView mesh, Method method, const MethodOptions& options = {});
std::unique_ptr<Classifier> makeClassifier(const GlContext& gl, MeshView mesh, Method method,
                                           const MethodOptions& options = {});
/// From a baked sprite: Method::Sprite or Method::SpriteGpu (the others need
/// the mesh; `InvalidArgument` says so).
std::unique_ptr<Classifier> makeClassifier(Sprite sprite, Method method);
std::unique_ptr<Classifier> makeClassifier(const GlContext& gl, Sprite sprite, Method method);

/// The baker `BakeMethod::Auto` means here: Cpu where no GL can be had,
/// else `chooseBakeMethod(gl)` on a private context (Lists on a GPU, Cpu
/// on a software renderer). `why` gets one line saying which and why.
BakeMethod chooseBakeMethod(std::string* why = nullptr);

/// Bakes `mesh` by `options.method` (Auto: `chooseBakeMethod()`): the CPU baker, or the GL bakers on a
/// private headless context (the caller's current context is current again
/// on return). Throws like `bakeCpu` and `bakeOnGl`, `GlUnavailable`
/// without GL.
Sprite bake(MeshView mesh, const BakeOptions& options);
/// The same on the caller's context: `bakeOnGl(gl, mesh, options)`.
Sprite bake(const GlContext& gl, MeshView mesh, const BakeOptions& options);

} // namespace vds
