// vds: the volumetric depth sprite and the volumetric parity test on the CPU.
//
// Trapp & Döllner, "Real-Time Volumetric Tests Using Layered Depth Images",
// Eurographics 2008 short paper, sections 3.1 (the VDS) and 3.2 (the VPT).
//
// A sprite VDS_S = (P_S, M_S, LDI_S, d_S). A world point P maps to LDI texture
// space as T = M_S * (P - P_S), T in [0,1]^3 inside the sprite's box. (T.s,T.t)
// pick a texel column of the layered depth image; T.r is the depth along the
// view axis. Each column stores the depths of the surface crossings of the ray
// through the texel centre, sorted front to back, with whether the surface
// faced the viewer there (the ray enters the solid) or not (it leaves).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vds/axis.h>
#include <vds/classify.h>
#include <vds/enum_names.h>
#include <vds/grid.h>
#include <vds/mesh.h>
#include <vds/rule.h>

namespace vds {

/// The texel grid of a sprite: how a mesh box becomes an LDI.
///
/// Texels are square in world units: `texelSize = max(extent_s, extent_t) /
/// resolution`, `width = ceil(extent_s / texelSize)`, likewise `height`. Texel
/// (i, j) covers s in [i, i+1) / width; its ray runs through its centre.
/// Depth r = (p_axis - lo_axis) / extent_axis, so the box spans r in [0, 1].
struct SpriteGrid {
    Box box;                    ///< the baked mesh's bounding box, mesh coordinates
    Axis axis = Axis::Z;
    std::uint32_t width = 0;    ///< texels along s
    std::uint32_t height = 0;   ///< texels along t
    float texelSize = 0.0f;     ///< world units
    glm::vec3 position{0.0f};   ///< P_S: world position of LDI texture-space origin
    glm::mat3 matrix{1.0f};     ///< M_S: world -> LDI texture space, linear part

    /// World point -> LDI texture space, computed exactly as the GLSL include does.
    glm::vec3 toTexture(const glm::vec3& world) const;
    /// Centre of texel (i, j) at depth r, in the mesh coordinates of the bake
    /// (the placement is not applied): the point a baker's ray runs through.
    glm::vec3 texelCentre(std::uint32_t i, std::uint32_t j, float r) const {
        const glm::ivec3 p = axisPermutation(axis);
        glm::vec3 c;
        c[p.x] = box.lo[p.x] + (float(i) + 0.5f) * texelSize;
        c[p.y] = box.lo[p.y] + (float(j) + 0.5f) * texelSize;
        c[p.z] = box.lo[p.z] + r * (box.hi[p.z] - box.lo[p.z]);
        return c;
    }
};

/// Largest resolution accepted anywhere (bake, voxel grids): 16384 texels.
constexpr std::uint32_t kMaxResolution = 16384;

/// Builds the grid for a box. Throws `InvalidArgument` for resolution 0 or
/// above `kMaxResolution`, or a box with no extent across or along the view.
SpriteGrid makeGrid(const Box& box, Axis axis, std::uint32_t resolution);

/// True when a regular grid can be swept through the sprite column by
/// column (the occupancy sweeps, CPU and GPU, take that path): each texture
/// axis follows one world axis (the sprite was moved, scaled, mirrored or
/// turned by quarter turns since the bake, not rotated by other angles) and
/// depth grows along the world axis r follows, so a column's cells meet its
/// crossings in order. Otherwise the sweeps ask each cell centre.
bool sweepsByColumns(const SpriteGrid& grid);

/// Encoding of one stored crossing: depth in [0,1], sign bit set when the ray
/// leaves the solid there (the surface faced away from the viewer). -0.0 is a
/// leaving crossing at depth 0. GLSL reads the same bits.
inline float encodeCrossing(float depth, bool entering) { return entering ? depth : -depth; }
inline bool crossingEnters(float encoded) { return !std::signbit(encoded); }
inline float crossingDepth(float encoded) { return std::fabs(encoded); }

/// Result of mesh validation recorded in a sprite.
enum class SolidStatus : std::uint8_t {
    Closed = 0, ///< `solidStatus`: every rule answers alike for the mesh's solid (non-manifold edges allowed)
    Open = 1,   ///< baked with a warning: boundary edges, or closed but mis-oriented (`statusWord` tells which)
};

/// A sprite's status for `MeshReport::status()`: Closed only where every
/// rule answers alike (`closed()` and not `misoriented()`).
SolidStatus solidStatus(const MeshReport& report);
/// A sprite's word for its mesh, `MeshReport::status()`'s, from its status
/// and validation summary (`Sprite::status`, `Sprite::validation`; files
/// of every version): "closed", "mis-oriented" or "open".
const char* statusWord(SolidStatus status, const std::string& validation);

/// A signed distance grid a sprite can carry, for `vdsDistance` in GLSL
/// (shaders/vds/vpt.glsl, within half a cell's diagonal of the exact signed
/// distance): `SignedDistance::grid` of the baked mesh by the bake's rule,
/// over `grid`, in the mesh coordinates of the bake (those of
/// `SpriteGrid::box`; the placement is not applied). Empty `cells`: none.
struct SpriteDistance {
    Grid grid;
    std::vector<float> cells; ///< grid.cellCount() floats in `Grid::index` order, or none
    bool empty() const { return cells.empty(); }
};

/// Largest cells along any side of a sprite's distance grid.
constexpr std::uint32_t kMaxDistanceResolution = 1024;

struct Sprite;

/// How a sprite's batch reads the sprite (`Method::Sprite` only).
enum class QueryLayout : std::uint8_t {
    Auto,    ///< Packed when the batch has at least half as many points as the sprite has columns
    Offsets, ///< the sprite's own arrays: offsets, then crossings (two dependent cache misses a point)
    /// A table of 16 bytes a column with its first four crossings (32 bytes
    /// and eight where many columns have more), built for the call in huge
    /// pages: one cache miss a point and no branch on the data, unless it
    /// lies behind those crossings. The same answers as Offsets.
    Packed,
};

/// How a sprite evaluates the boundary term of Rule::GeneralizedWinding.
enum class BoundaryEvaluation : std::uint8_t {
    /// The boundary's loops and chains closed by fans (the caps): a
    /// coarse grid of proven ranges of the term answers most points, a tree
    /// of chords and multipole expansions with proven error bounds the
    /// rest, and the per-edge sum wherever those bounds could change a
    /// label. The same labels as Exact; about O(log edges) a point near the
    /// boundary, O(1) in most of the box. Built once per
    /// SpriteClassifier (once per call of the free `classify`).
    Caps,
    Exact, ///< the per-edge sum for every point: O(boundary edges) a point
};


/// How a sprite answers a batch: fixed when its `SpriteClassifier` is made
/// (or passed to the free `classify` beside the per-query options).
struct SpriteQueryOptions {
    QueryLayout layout = QueryLayout::Auto;
    /// Rule::GeneralizedWinding on sprites with boundary edges only.
    BoundaryEvaluation boundary = BoundaryEvaluation::Caps;
};

/// A volumetric depth sprite held in host memory.
///
/// The LDI is stored compressed-row style: column c = j * width + i holds
/// `crossings[offsets[c] .. offsets[c+1])`, encoded with `encodeCrossing`,
/// sorted by depth (ties by the triangle order of the baked mesh). The dense
/// form the paper uses (width x height x depthComplexity, padded with 1.0) is
/// built only for upload to GL.
struct Sprite {
    /// 3: an optional distance grid (`distance`); a sprite without one is
    /// written as version 2, which older readers read. 2: the boundary edges
    /// are stored (`boundaryEdges`). Version 1 files still read, with no
    /// boundary edges.
    static constexpr int kFormatVersion = 3;

    SpriteGrid grid;
    std::uint32_t depthComplexity = 0;      ///< d_S: the most crossings in any column
    std::vector<std::uint32_t> offsets;     ///< width*height + 1 entries
    std::vector<float> crossings;           ///< encoded crossings, all columns
    std::string sourceName;                 ///< mesh file name, informational
    std::uint64_t sourceTriangles = 0;
    SolidStatus status = SolidStatus::Closed;
    std::string validation;                 ///< `MeshReport::summary()` at bake time
    /// The baked mesh's boundary edges, for Rule::GeneralizedWinding: edge k
    /// runs from `boundaryEdges[2k]` to `boundaryEdges[2k+1]`, in the mesh
    /// coordinates of the bake (those of `grid.box`; the placement is not
    /// applied). Edges whose uses do not cancel after welding vertices with
    /// equal positions, an edge repeated by how many more times it is used
    /// one way than the other (non-manifold edges count by their unbalanced
    /// orientation), oriented as the majority of its triangles run it. Empty
    /// for a mesh whose every edge is used equally often each way.
    std::vector<glm::vec3> boundaryEdges;
    /// False only for a sprite of an open mesh read from a version-1 file:
    /// its boundary was never stored, and Rule::GeneralizedWinding refuses it.
    bool boundaryKnown = true;
    /// An optional signed distance grid of the baked mesh (`bakeDistance`,
    /// `vds bake --distance N`), stored by format version 3; empty otherwise.
    SpriteDistance distance;

    std::uint32_t width() const { return grid.width; }
    std::uint32_t height() const { return grid.height; }

    /// Inside test of one world point (the sprite's placement applied).
    /// Points outside the box [0,1]^3 in texture space are outside. A point
    /// exactly at a stored depth does not count that crossing: on an entering
    /// surface it is outside, on a leaving one inside.
    /// With Rule::GeneralizedWinding: `generalizedWinding(world) > 1/2`, by
    /// the per-edge sum (O(boundary edges) a point; a `SpriteClassifier`
    /// builds the caps once and answers batches from them, same labels).
    bool contains(const glm::vec3& world, Rule rule = Rule::Parity) const;

    /// The generalized winding number at a world point, by the Antipodal
    /// split (Martens, Trettner & Bessmeltsev 2026): the signed count of the
    /// point's column in front of it, plus the boundary term (the sum over
    /// `boundaryEdges` of the solid angle of the spherical triangle (+axis,
    /// a - q, b - q) over 4 pi, in double) taken at q, the point moved
    /// across the axis onto its texel's centre ray (same depth). The count
    /// belongs to that ray, so both terms are taken at q and their jumps
    /// cancel: the value is the exact GWN at q, up to the rounding of the
    /// stored depths. So it errs only by GWN(q) - GWN(p), |p - q| <= texel *
    /// sqrt(2) / 2: a label differs from the exact one only where the GWN
    /// crosses 1/2 within 0.71 texel of p across the axis, i.e. within that
    /// distance of the surface (where the GWN jumps by 1) or where its
    /// gradient, at most (1/4 pi) * (boundary length) / d^2 at distance d
    /// from the boundary curve, times 0.71 texel exceeds |GWN - 1/2|.
    /// Points outside the box get 0 (the sprite knows nothing there; the
    /// GWN of a surface inside a box is at most 1/2 outside it for a
    /// surface that covers no direction twice). Without boundary edges the
    /// value is the winding number. The boundary term is the per-edge sum,
    /// O(boundary edges) a call. Throws `InvalidArgument` when
    /// `boundaryKnown` is false.
    double generalizedWinding(const glm::vec3& world) const;

    /// Moves the sprite by `model`, on top of its current placement: a sprite
    /// that answered for solid S answers for model(S) afterwards, without
    /// re-baking. `model` must be affine and invertible (throws
    /// `InvalidArgument` otherwise).
    void transform(const glm::mat4& model);

    /// Bytes of host memory the LDI takes here (offsets + crossings).
    std::size_t memoryBytes() const;
    /// Bytes of the paper's dense float texture: width * height * d_S * 4.
    std::size_t denseBytes() const;

    /// Throws `FormatError` if the arrays disagree with each other or the grid
    /// (sizes, sorting, depth range, d_S), or a distance grid is malformed
    /// (its cell count, a box that is not finite or empty, a value that is
    /// not finite). Used by the reader; cheap, O(n).
    void checkConsistent() const;
};

/// The engine under `SpriteClassifier` (the engine layer of <vds/vds.h>):
/// the sprite's answers for `points` (world coordinates, the placement
/// applied), the same answers as `Sprite::contains`, batched on
/// `options.threads` threads (the sprite is only read), read as `query`
/// says. Rule::GeneralizedWinding with `BoundaryEvaluation::Caps` builds the
/// caps for this call alone: ask a `SpriteClassifier`, which keeps them,
/// for more than one batch.
void classify(const Sprite& sprite, const PointsView& points, std::uint8_t* labels,
              const ClassifyOptions& options = {}, const SpriteQueryOptions& query = {});

/// `Method::Sprite` as a `Classifier` (<vds/classify.h>): owns its sprite,
/// answers every batch as `query` says and keeps the sprite's caps for
/// Rule::GeneralizedWinding (built by the first such query).
class SpriteClassifier final : public Classifier {
public:
    explicit SpriteClassifier(Sprite sprite, const SpriteQueryOptions& query = {});
    /// A copy holds the same sprite and options; its caps start unbuilt.
    SpriteClassifier(const SpriteClassifier& other);
    /// The caps move along; the moved-from classifier's queries build their own.
    SpriteClassifier(SpriteClassifier&& other) noexcept;
    SpriteClassifier& operator=(const SpriteClassifier& other);
    SpriteClassifier& operator=(SpriteClassifier&& other) noexcept;
    ~SpriteClassifier() override;
    const Sprite& sprite() const { return sprite_; }
    const SpriteQueryOptions& query() const { return query_; }
    Method method() const override { return Method::Sprite; }
    std::size_t memoryBytes() const override;
    std::string summary() const override;

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;
    void sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const override;

private:
    /// The sprite's boundary loops and caps for Rule::GeneralizedWinding,
    /// built by the first such query, thread safe (internal).
    struct Caps;
    Sprite sprite_;
    SpriteQueryOptions query_;
    std::unique_ptr<Caps> caps_; ///< null only in a moved-from classifier
};

} // namespace vds
