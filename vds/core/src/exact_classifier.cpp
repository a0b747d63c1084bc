// vds: exact point-in-solid classification on the triangles themselves.
//
// Trapp & Döllner 2008, section 3.2 (the parity test: count the surface
// crossings of a ray in front of the point), evaluated with exact predicates
// and the top-left tie rule of projected_mesh.h.
#include <vds/exact.h>

#include <cassert>
#include <cstring>

#include <vds/parallel.h>

#include "projected_mesh.h"

namespace vds {

struct ExactClassifier::Impl : detail::ProjectedMesh {
    using detail::ProjectedMesh::ProjectedMesh;
};

ExactClassifier::ExactClassifier(MeshView mesh, Axis axis) {
    requireUsable(validateMesh(mesh), "mesh");
    impl_ = std::make_unique<Impl>(mesh, axis);
}

ExactClassifier::~ExactClassifier() = default;
ExactClassifier::ExactClassifier(ExactClassifier&&) noexcept = default;
ExactClassifier& ExactClassifier::operator=(ExactClassifier&&) noexcept = default;

Axis ExactClassifier::axis() const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->axis;
}

int ExactClassifier::winding(const glm::vec3& p) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->winding(p);
}

namespace {
// Each crossing is +1 or -1, so the crossing count and the winding number
// have the same parity.
bool inside(int winding, Rule rule) { return rule == Rule::Parity ? (winding & 1) != 0 : winding != 0; }
} // namespace

bool ExactClassifier::contains(const glm::vec3& p, Rule rule) const { return inside(winding(p), rule); }

bool ExactClassifier::containsBruteForce(const glm::vec3& p, Rule rule) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return inside(impl_->windingBruteForce(p), rule);
}

void ExactClassifier::classify(const glm::vec3* points, std::size_t count, std::uint8_t* labels,
                               const ClassifyOptions& options) const {
    classify(reinterpret_cast<const float*>(points), count, sizeof(glm::vec3), labels, options);
}

void ExactClassifier::classify(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                               const ClassifyOptions& options) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    assert(strideBytes >= 3 * sizeof(float) && ((xyz && labels) || count == 0));
    const Impl& impl = *impl_;
    const char* base = reinterpret_cast<const char*>(xyz);
    parallelFor(options.threads, count, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            glm::vec3 p;
            std::memcpy(&p, base + k * strideBytes, sizeof p);
            labels[k] = inside(impl.winding(p), options.rule) ? 1 : 0;
        }
    });
}

// ---- The CPU baker --------------------------------------------------------

} // namespace vds
