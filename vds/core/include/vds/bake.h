// vds: baking a closed triangle mesh into a volumetric depth sprite.
//
// Trapp & Döllner 2008, section 4.1: the mesh box is mapped into the unit
// cube, viewed orthographically along one axis, and every surface crossing of
// every texel's ray is recorded. Three bakers produce the same layers:
//  - Peel:  classic depth peeling, one layer per pass, d_S found with an
//           occlusion query (the paper's method);
//  - Lists: one pass of per-pixel fragment lists, sorted per pixel in a
//           compute pass (the default: fastest on llvmpipe and GPUs);
//  - Cpu:   exact ray casting on the CPU (<vds/exact.h>), no GL needed.
// Crossings at equal depth are ordered by triangle index in all three.
//
// Which layer bakes: `bake()` lives in vds::core and runs the Cpu method
// itself. The GL methods live in vds::gl, which registers them with `bake()`
// when it is linked (a registry rather than a second entry point, so that
// code written against the single library keeps calling `bake(mesh, {})`).
// A program that links vds::core alone gets `GlUnavailable` for Peel and
// Lists, with a message that says to link vds::gl or use BakeMethod::Cpu.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds {

class GlContext;

enum class BakeMethod : std::uint8_t { Peel, Lists, Cpu };

template <> struct EnumNames<BakeMethod> {
    static constexpr const char* kind = "bake method";
    static constexpr EnumName<BakeMethod> table[] = {
        {"lists", BakeMethod::Lists}, {"peel", BakeMethod::Peel}, {"cpu", BakeMethod::Cpu}};
};

/// Parses "peel" / "lists" / "cpu"; throws `InvalidArgument`.
BakeMethod parseBakeMethod(const std::string& s);
const char* toString(BakeMethod m);

struct BakeOptions {
    std::uint32_t resolution = 1024;        ///< texels on the longer side of the view, 1..16384
    Axis axis = Axis::Z;                    ///< view direction
    BakeMethod method = BakeMethod::Lists;
    std::string sourceName;                 ///< recorded in the sprite (e.g. the mesh file name)
    /// Fragment-list node pool limit in nodes; 0 = as many as one GL buffer
    /// may hold. When a pass needs more, the image is baked in row bands.
    std::uint64_t maxListNodes = 0;
    /// Called now and then with a short description of the work in progress.
    std::function<void(const std::string&)> progress;
};

/// The view axis with the fewest layers (the least depth complexity d_S; ties
/// go to fewer crossings in all), found by exact CPU bakes at a coarse
/// `probeResolution` along x, y and z. Trapp & Doellner 2008, section 6, name
/// this "optimal view direction" as future work: fewer layers mean a smaller
/// texture and fewer lookups per test. Throws like `bake`.
Axis chooseViewAxis(MeshView mesh, std::uint32_t probeResolution = 64);

/// Bakes `mesh`. Validates it first: empty meshes, non-finite coordinates and
/// bad indices throw `InvalidMesh`; an open or inconsistently oriented mesh is
/// baked, its sprite marked `SolidStatus::Open` (the caller should warn: the
/// answers are those of a surface, not a solid). A closed, oriented mesh with
/// non-manifold edges bounds a solid and is marked `SolidStatus::Closed`. GL methods use `gl` if given (made
/// current for the call), else make a private context for the call; either
/// way the calling thread's current context is the same on return. Throws
/// `GlUnavailable` if no GL can be had or vds::gl is not linked.
Sprite bake(MeshView mesh, const BakeOptions& options, GlContext* gl = nullptr);

/// The CPU baker: the sprite the GL bakers make, by exact ray casting at
/// texel centres (`bake()` calls this for `BakeMethod::Cpu`). A column holds
/// one crossing per triangle whose projection claims the texel centre (the
/// rule of `ExactClassifier`, <vds/exact.h>), at the depth of the triangle's
/// plane there in LDI texture space, sorted by depth, then triangle index.
/// Validates like `bake()` (throws `InvalidMesh`); `options.maxListNodes` is
/// ignored. Runs on every hardware thread; `options.progress` is called on
/// the calling thread.
Sprite bakeCpu(MeshView mesh, const BakeOptions& options);

namespace detail {
/// A GL baker as vds::gl registers it: fills the CSR layers (`offsets`,
/// `crossings`, see `Sprite`) of `grid` for a mesh `bake()` has validated.
/// `gl` may be null (the baker then makes its own context).
using LayerBaker = void (*)(MeshView mesh, const SpriteGrid& grid, const BakeOptions& options, GlContext* gl,
                            std::vector<std::uint32_t>& offsets, std::vector<float>& crossings);
/// Called by vds::gl at load time; not for users.
void registerLayerBaker(BakeMethod method, LayerBaker baker) noexcept;
} // namespace detail

} // namespace vds
