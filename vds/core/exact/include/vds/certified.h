// vds: certified classification — the exact classifier's answers at close
// to a sprite's speed.
//
// A sprite errs only near the surface, and a bake can tell where "near" is.
// For each texel of a grid over the mesh's box (as a sprite's, along one
// axis) the bake collects every triangle whose projection meets the texel's
// footprint (widened by 1/64 texel for the rounding of the texel lookup)
// and the depth interval that triangle's plane can take over the footprint
// (its values at the footprint's corners, cut to the triangle's own depth
// range, computed in double and rounded outwards to float). The union of
// these intervals, merged, is the column's *uncertain bands*.
//
// Why the gaps between bands are certain: take a point p in the footprint
// whose depth z lies in no band. The horizontal square {footprint} x {z}
// meets no triangle (every triangle that reaches the footprint stays
// strictly above or below z there), so, when the mesh bounds a solid, every
// point of the square is on the same side of the surface as p. One of them
// is the texel centre at depth z, whose exact answer the bake knows: it
// counts the triangles the centre's ray claims (the exact classifier's
// top-left rule, <vds/exact.h>), each of which lies in a band below or
// above z. So every gap of every column carries a winding number, and a
// query whose depth falls in a gap is answered from it; a query in a band,
// on the footprint's outer boundary, or on a mesh that does not bound a
// solid goes to the exact classifier. Answers therefore equal
// `ExactClassifier(mesh, axis)` everywhere; points off the surface get the
// solid's true answer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <glm/vec3.hpp>

#include <vds/axis.h>
#include <vds/classify.h>
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds {

/// One uncertain band of a column: the surface may lie at depths [lo, hi]
/// (mesh units along the grid's axis), nowhere else in the gap up to the
/// next band; `windingAbove` is the winding number of the gap above it
/// (the gap below a column's first band has winding 0).
struct CertifiedBand {
    float lo, hi;
    std::int32_t windingAbove;
};

/// The bands of a `CertifiedClassifier`, read-only views into it (valid
/// while it lives, unchanged by queries): what its GPU form uploads and
/// what shaders/vds/certified.glsl reads. A point p of mesh coordinates is
/// answered from them when `certifiedRules` has its rule's bit, p lies
/// strictly inside `box`, and its depth p[depthAxis] lies in no band of
/// its column (the grid's texel of p, `SpriteGrid::toTexture`); finite
/// points outside `box` are outside; every other point needs the exact
/// classifier.
struct CertifiedBands {
    /// `columnCount + 1` entries (none when `certifiedRules` is 0): column
    /// c = j * width + i of the grid has bands [offsets[c], offsets[c+1]),
    /// sorted by depth, disjoint.
    const std::uint32_t* offsets = nullptr;
    std::size_t columnCount = 0;
    const CertifiedBand* bands = nullptr;
    std::size_t bandCount = 0;
    Box box;              ///< the mesh's bounds, mesh coordinates
    int depthAxis = 2;    ///< 0, 1, 2: the grid's axis x, y, z
    std::uint8_t certifiedRules = 0; ///< bit (1 << Rule) for each rule the bands answer
};

struct CertifiedOptions {
    std::uint32_t resolution = 1024; ///< texels on the longer side of the grid, as for a sprite (1..16384)
    Axis axis = Axis::Z;
    unsigned threads = 0; ///< for building; 0: one per hardware thread
};

class CertifiedClassifier final : public Classifier {
public:
    /// Copies the mesh's triangles, builds the exact classifier and the
    /// bands. Throws `InvalidMesh` for an unusable mesh, `InvalidArgument`
    /// for a resolution out of range. A mesh that does not bound a solid
    /// (`MeshReport::closed()` false) is accepted: every query then takes
    /// the exact path.
    explicit CertifiedClassifier(MeshView mesh, const CertifiedOptions& options = {});
    ~CertifiedClassifier();
    CertifiedClassifier(CertifiedClassifier&&) noexcept;
    CertifiedClassifier& operator=(CertifiedClassifier&&) noexcept;

    /// The exact classifier's answer for `p` (mesh coordinates).
    bool contains(const glm::vec3& p, Rule rule = Rule::Parity) const;

    /// Batches go through `Classifier::classify` (<vds/classify.h>);
    /// `options.stats`, if set, receives how many points the bands answered
    /// (`certain`) and how many the exact classifier (`exact`).
    Method method() const override { return Method::Certified; }
    /// The bands and the exact classifier behind them.
    std::size_t memoryBytes() const override;
    std::string summary() const override;

    /// False when the mesh does not bound a solid (`MeshReport::closed()`):
    /// every answer is then the exact classifier's own. The winding rules
    /// are certified only for oriented meshes (`MeshReport::oriented()`).
    bool certifies() const;
    /// The grid of the bands (as a sprite baked with the same options would have).
    const SpriteGrid& grid() const;
    /// The bands themselves, for GPU forms and shaders (see `CertifiedBands`).
    CertifiedBands bands() const;
    /// Bytes of the bands (offsets, intervals, windings), without the exact classifier.
    std::size_t bandBytes() const;
    /// The exact classifier behind it.
    const ExactClassifier& exact() const;

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace vds
