// vds: exact point-in-solid classification on the triangles themselves.
//
// The yardstick for every approximate representation in the project, and a
// CPU baker. A ray is shot from the point towards -axis (the sprite's viewer
// side); each triangle whose projection along the axis contains the point's
// projection, and that lies in front of the point, is one crossing. Evaluated
// at texel centres this yields exactly the crossings of an LDI column.
//
// Robustness: the 2D point-in-triangle test uses exact orientation predicates
// and a top-left tie rule (as hardware rasterizers do), so a ray through a
// shared edge or vertex of a closed mesh counts exactly one crossing. A point
// exactly on the surface follows the sprite's convention: a crossing at the
// point's own depth is not counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/axis.h>
#include <vds/classify.h>
#include <vds/mesh.h>
#include <vds/rule.h>
#include <vds/sprite.h>

namespace vds {

/// Exact classifier over a copy of a mesh's triangles, with an acceleration
/// structure over their projections along `axis` (a uniform grid; about 100
/// bytes per triangle). Construction is O(n log n); queries are thread safe.
///
/// Points are in mesh coordinates; any point may be asked (points off the
/// mesh's projection, and non-finite ones, are outside). A point on an edge
/// or vertex of the projection is claimed by the triangles that contain the
/// point moved by (eps, -eps^2) in (s,t), eps infinitesimal: the top-left
/// fill rule with t up. So a ray through a shared edge or vertex of a closed
/// mesh counts one crossing per surface sheet. Triangles parallel to the
/// axis are never crossed.
class ExactClassifier final : public Classifier {
public:
    /// Copies the triangles. Throws `InvalidMesh` if the mesh is not usable
    /// (empty, non-finite, bad indices).
    explicit ExactClassifier(MeshView mesh, Axis axis = Axis::Z);
    ~ExactClassifier();
    ExactClassifier(ExactClassifier&&) noexcept;
    ExactClassifier& operator=(ExactClassifier&&) noexcept;

    Axis axis() const;

    /// Winding number of `p`: crossings strictly in front of p (smaller depth,
    /// towards -axis) count +1 where the surface faces the viewer (its
    /// outward normal points towards -axis: the ray enters), -1 elsewhere.
    int winding(const glm::vec3& p) const;
    /// The generalized winding number of `p` (see Rule::GeneralizedWinding):
    /// `winding(p)` plus the boundary term of the Antipodal method (Martens,
    /// Trettner & Bessmeltsev 2026), the solid angles of the spherical
    /// triangles (+axis, a - p, b - p) over every boundary edge a -> b, over
    /// 4 pi, in double. Equals `winding(p)` on a mesh without boundary. On
    /// the surface or the boundary curve the value is still defined (the
    /// tie rule decides the integer term; a degenerate spherical triangle
    /// adds 0) but it need not be continuous there. O(boundary edges) a call.
    double generalizedWinding(const glm::vec3& p) const;
    /// Edges whose uses do not cancel, counted with their multiplicity
    /// (after welding vertices with equal positions).
    std::size_t boundaryEdgeCount() const;
    /// Parity (odd crossings), non-zero winding, or generalized winding > 1/2.
    bool contains(const glm::vec3& p, Rule rule = Rule::Parity) const;
    /// The same answer as `contains`, by testing every triangle (no
    /// acceleration structure, O(triangles) a point): the reference the
    /// accelerated path is held to, for tests and benchmarks.
    bool containsByEveryTriangle(const glm::vec3& p, Rule rule = Rule::Parity) const;
    /// Batches go through `Classifier::classify` (<vds/classify.h>); every
    /// rule is answered.
    Method method() const override { return Method::Exact; }
    std::size_t memoryBytes() const override;
    std::string summary() const override;

protected:
    void classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                        const ClassifyOptions& options) const override;
    /// Along z: one sweep per column (the labels of `occupancy(mesh, ...)`).
    void sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const override;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The CPU baker, `bakeCpu`, is declared in <vds/bake.h>.

} // namespace vds
