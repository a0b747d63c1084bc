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
#include <vector>

#include <glm/vec3.hpp>

#include <vds/bake.h>
#include <vds/mesh.h>
#include <vds/sprite.h>

namespace vds {

/// Exact classifier over a copy of a mesh's triangles, with an acceleration
/// structure over their projections along `axis`. Construction is O(n log n);
/// queries are thread safe.
class ExactClassifier {
public:
    /// Copies the triangles. Throws `InvalidMesh` if the mesh is not usable
    /// (empty, non-finite, bad indices).
    explicit ExactClassifier(MeshView mesh, Axis axis = Axis::Z);
    ~ExactClassifier();
    ExactClassifier(ExactClassifier&&) noexcept;
    ExactClassifier& operator=(ExactClassifier&&) noexcept;

    Axis axis() const;

    /// Winding number of `p`: crossings in front of p (towards -axis) entering
    /// count +1, leaving -1.
    int winding(const glm::vec3& p) const;
    /// Parity (odd crossings) or non-zero winding.
    bool contains(const glm::vec3& p, Rule rule = Rule::Parity) const;
    /// Batch form; `labels[k]` = 1 inside, 0 outside.
    void classify(const glm::vec3* points, std::size_t count, std::uint8_t* labels,
                  const ClassifyOptions& options = {}) const;

    /// Same answer as `contains`, by a loop over every triangle (no
    /// acceleration): the reference the accelerated path is tested against.
    bool containsBruteForce(const glm::vec3& p, Rule rule = Rule::Parity) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// CPU baker: the sprite the GL bakers make, by exact ray casting at texel
/// centres (`bake()` calls this for `BakeMethod::Cpu`). Multi-threaded.
Sprite bakeCpu(MeshView mesh, const BakeOptions& options);

} // namespace vds
