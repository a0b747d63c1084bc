// Samples: a model clipped and styled by solids, rendered offscreen through
// vds/styles.glsl with the inside test of a VDS, a slicemap, solid voxels or
// the exact classifier (the reference), plus the numbers the comparison
// needs: differing pixels, GPU frame time, memory.
//
// World coordinates are the model's mesh coordinates. Each solid is a closed
// mesh in its own coordinates placed in the world by a matrix; moving it
// (`SceneRenderer::place`) re-uploads a placement, never re-bakes.
//
// Everything here needs the GlContext it was made on to be current.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vds/eval/image.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds::samples {

/// Which inside test the fragment shader runs.
enum class Lookup : std::uint8_t { Vds, Slicemap, SlicemapLocal, Solid, Exact };
/// "vds", "slicemap", "slicemap-local", "solid", "exact"; throws InvalidArgument.
Lookup parseLookup(const std::string& name);
const char* toString(Lookup lookup);

/// A solid's role (the values of VDS_ROLE_* in shaders/vds/styles.glsl).
enum class Role : int { Off = 0, ClipAway = 1, ClipTo = 2, Style = 3, Lens = 4 };
/// How solids of one clip role combine (VDS_COMBINE_*).
enum class Combine : int { Union = 0, Intersection = 1 };
/// Style ids of shaders/samples/scene.frag.
enum class Style : int { Shaded = 1, Gouraud = 2, XRay = 3, Blueprint = 4 };

struct SceneSolid {
    std::string name;
    TriangleMesh mesh;              ///< closed, its own coordinates (may be empty when `sprite` is given)
    std::optional<Sprite> sprite;   ///< a baked sprite of the solid (Lookup::Vds only; else baked from `mesh`)
    glm::mat4 placement{1.0f};      ///< mesh coordinates -> world
    Role role = Role::ClipAway;
    Style style = Style::Shaded;    ///< for Role::Style and Role::Lens
};

struct Scene {
    std::string name;
    TriangleMesh model;             ///< the rendered mesh, world coordinates
    std::vector<SceneSolid> solids; ///< 1..8
    Combine combineAway = Combine::Union;
    Combine combineTo = Combine::Union;
    Style baseStyle = Style::Shaded;
    Rule rule = Rule::Parity; ///< inside rule of the VDS and exact lookups (voxels have their own)
    glm::vec3 viewDirection{0.8f, 0.55f, 1.0f}; ///< from the model's centre towards the camera
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    /// World units; > 0 turns on the distance effects of scene.frag, read
    /// through `vdsDistance` from each solid's distance grid (Lookup::Vds
    /// only): a band of this width in `bandColour` where a clip solid cuts
    /// the surface (|d| <= width), and a soft lens edge (the X-ray fades in
    /// over this width inside the border, a glow fades out over it outside).
    float distanceWidth = 0.0f;
    /// Cells along the longest side of the distance grid baked for a solid
    /// given as a mesh (`bakeDistance`); a sprite brings its own grid.
    std::uint32_t distanceResolution = 64;
    glm::vec3 bandColour{1.0f, 0.62f, 0.08f};
};

/// The bundled meshes and generated solids, and the gallery's scenes.
TriangleMesh uvSphere(const glm::vec3& centre, float radius, int rings);
TriangleMesh box(const glm::vec3& lo, const glm::vec3& hi);
/// `dataDir` holds spot.obj and lens.obj (samples/data).
Scene clipScene(const std::string& dataDir, Combine combine);
Scene lensScene(const std::string& dataDir);
/// The lens's placement at path parameter t in [0, 1] (a sweep across Spot).
glm::mat4 lensPath(float t);
Scene stylesScene(const std::string& dataDir);

/// Representation size: cells (voxel) or texels (VDS) along the solid's
/// longest side, or, with `equalMemoryTo`, a voxel resolution chosen per
/// solid so its GPU bytes come closest to (not above) a VDS of that
/// resolution.
struct RepresentationSize {
    std::uint32_t resolution = 256;
    bool equalMemory = false;
};

class SceneRenderer {
public:
    /// Builds the representation of every solid (bakes sprites, builds voxel
    /// models, or exact classifiers) and the programs, on `gl` (current).
    /// Throws vds::Error subclasses (InvalidArgument for more than 8 solids
    /// or a sprite-only solid with a voxel lookup, InvalidMesh, GlError).
    SceneRenderer(const GlContext& gl, const Scene& scene, Lookup lookup, RepresentationSize size = {});
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    /// Replaces solid `index`'s sprite by `sprite` (a re-bake of a solid
    /// whose vertices moved: `Baker::rebake`), at the solid's placement.
    /// Lookup::Vds only; throws InvalidArgument otherwise, and when the
    /// scene draws its distance effects (`Scene::distanceWidth`) and
    /// `sprite` carries no distance grid.
    void replaceSprite(std::size_t index, const Sprite& sprite);
    /// Moves solid `index` to `placement` (mesh -> world) without re-baking.
    void place(std::size_t index, const glm::mat4& placement);
    /// Renders a `size` x `size` picture.
    eval::Image render(std::uint32_t size);
    /// Renders a `width` x `height` picture; the camera sees the model's
    /// bounding sphere across the shorter side (a square picture is render(size)'s).
    eval::Image render(std::uint32_t width, std::uint32_t height);
    /// Draws the scene into `framebuffer` (0: the window's) at `width` x
    /// `height` (offscreen, then copied), for a window's frame loop: the context must be current; the
    /// exact lookup peels again only when a solid moved or the size changed.
    void drawTo(unsigned framebuffer, std::uint32_t width, std::uint32_t height);
    /// The camera of a `width` x `height` picture: world -> clip space.
    glm::mat4 viewProjection(std::uint32_t width, std::uint32_t height) const;
    /// Changes what solid `index` does (role, style) without re-baking.
    void setRole(std::size_t index, Role role, Style style);
    /// Changes the style outside every solid and how clip solids combine.
    void setStyles(Style baseStyle, Combine combineAway, Combine combineTo);
    /// The scene with the solids' current placements.
    const Scene& scene() const;
    /// GPU time of the shading passes of one frame (GL_TIME_ELAPSED), the
    /// median over `repeats` frames, in milliseconds; the exact lookup times
    /// its shading passes only (the CPU classification is not in it).
    double frameMilliseconds(std::uint32_t size, int repeats = 5);
    /// Bytes of the GL objects the inside tests read, over every solid.
    std::size_t memoryBytes() const;
    /// Per solid, e.g. "lens: vds 256x256x4 texels, 1.0 MiB".
    std::vector<std::string> describe() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Pixels that differ (any channel) and a picture of them: unchanged pixels
/// faded to grey, differing ones red.
struct ImageDifference {
    std::size_t pixels = 0;     ///< pixels with any channel differing by more than `threshold`
    std::size_t covered = 0;    ///< pixels not background in either picture
    int max = 0;                ///< largest channel difference
    double mean = 0.0;          ///< mean channel difference over every pixel
    eval::Image picture;
};
ImageDifference compareImages(const eval::Image& image, const eval::Image& reference, int threshold = 8);

} // namespace vds::samples
