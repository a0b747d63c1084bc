// vds: re-baking a deforming mesh. The seed paper calls its method "limited
// to static meshes because animated shapes require a re-computation of its
// VDS"; with a bake of milliseconds of GPU time a mesh whose vertices move
// every frame can be re-baked every frame, if nothing but the bake runs.
// `Baker` validates the mesh's topology and chooses the view axis once;
// `updateVertices` then `rebake` costs the vertices' bounds (memory speed)
// and the bake itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/bake.h>
#include <vds/gl/context.h>
#include <vds/mesh.h>

namespace vds {

class Baker {
public:
    /// Validates `mesh` (throws like `bakeCpu`: an unusable or flat mesh, a
    /// resolution out of range) and chooses the axis (`options.axis`, or
    /// `chooseViewAxis` at `options.resolution` when unset) once. Bakes with
    /// `options.method` on `gl` (Auto: `chooseBakeMethod(gl)`), which must
    /// outlive the baker and is made current for each `rebake`.
    Baker(const GlContext& gl, TriangleMesh mesh, BakeOptions options);
    /// The same with no GL: `options.method` must be Cpu or Auto (which
    /// then means Cpu); throws `InvalidArgument` otherwise.
    Baker(TriangleMesh mesh, BakeOptions options);

    /// The vertices' new positions, as many as the mesh has, in the same
    /// order (the triangles stay). Throws `InvalidArgument` for another
    /// count and `InvalidMesh` for a NaN or infinite coordinate, leaving the
    /// old positions in place. The topology's validation is kept: where
    /// vertices come to coincide or triangles to collapse, the sprite's
    /// `validation` line still says what the first validation found.
    void updateVertices(const glm::vec3* positions, std::size_t count);
    void updateVertices(const std::vector<glm::vec3>& positions) { updateVertices(positions.data(), positions.size()); }

    /// Bakes the current vertices along the kept axis, in a box fitted to
    /// them: equal, bit for bit, to `bake`/`bakeOnGl` of the same mesh with
    /// `options.axis` set to `axis()` wherever the first validation still
    /// holds. Fills `options.timings` if set (Validation: the bounds).
    Sprite rebake();

    const TriangleMesh& mesh() const { return mesh_; }
    const MeshReport& report() const { return report_; }
    Axis axis() const { return *options_.axis; }

private:
    void validate();
    const GlContext* gl_ = nullptr; ///< none: the CPU baker
    TriangleMesh mesh_;
    BakeOptions options_;
    MeshReport report_;
    std::vector<std::uint32_t> used_; ///< the vertices the triangles name, each once: the box's
};

} // namespace vds
