// vds: exact point-in-solid classification on the triangles themselves.
//
// Trapp & Döllner 2008, section 3.2 (the parity test: count the surface
// crossings of a ray in front of the point), evaluated with exact predicates
// and the top-left tie rule of projected_mesh.h.
//
// The generalized winding number (Jacobson et al. 2013, "Robust
// Inside-Outside Segmentation using Generalized Winding Numbers") by the
// Antipodal method's split (Martens, Trettner & Bessmeltsev 2026): the
// integer term is the signed crossing count above, along the ray from p
// towards -axis; the boundary term sums, over the mesh's boundary edges
// (a -> b as the triangles run, repeated by their unbalanced multiplicity),
// the signed solid angle of the spherical triangle (+axis, a - p, b - p)
// over 4 pi. Where the ray passes over the boundary curve the integer term
// jumps by one and the boundary term by minus one, so the sum is the smooth
// GWN. The solid angle is Van Oosterom & Strackee's formula in double.
#include <vds/exact.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include <vds/detail/parallel.h>

#include <vds/detail/antipodal.h>
#include <vds/detail/boundary_caps.h>
#include <vds/detail/projected_mesh.h>

namespace vds {

namespace {

struct BoundaryEdge {
    glm::dvec3 a, b; ///< oriented as the triangles run on the side that has them
};

std::vector<BoundaryEdge> toDouble(const std::vector<glm::vec3>& ends) {
    std::vector<BoundaryEdge> edges(ends.size() / 2);
    for (std::size_t k = 0; k < edges.size(); ++k) edges[k] = {glm::dvec3(ends[2 * k]), glm::dvec3(ends[2 * k + 1])};
    return edges;
}

} // namespace

struct ExactClassifier::Impl : detail::ProjectedMesh {
    Impl(MeshView mesh, Axis viewAxis)
        : detail::ProjectedMesh(mesh, viewAxis), boundaryEnds(detail::boundaryEdges(mesh)), boundary(toDouble(boundaryEnds)),
          surface(*this) {
        const Box box = meshBounds(mesh);
        if (!boundaryEnds.empty())
            caps.emplace(boundaryEnds.data(), boundaryEnds.size() / 2, viewAxis, &box, &surface);
    }
    std::vector<glm::vec3> boundaryEnds; ///< as `Sprite::boundaryEdges`: 2 points an edge
    int axisIndex = axisPermutation(axis).z; ///< +axis: the apex of every boundary term's spherical triangle
    std::vector<BoundaryEdge> boundary;
    /// The triangles, for the caps' ranges of the whole winding number.
    detail::ProjectedSurface surface;
    /// The boundary's capped loops: labels equal to the per-edge sum's,
    /// without summing every edge for most points (boundary_caps.h).
    std::optional<detail::BoundaryCaps> caps;

    double boundaryTerm(const glm::vec3& p) const {
        return detail::boundaryTermExact(boundaryEnds.data(), boundaryEnds.size() / 2, axisIndex, glm::dvec3(p));
    }
    double generalizedWinding(const glm::vec3& p) const { return double(winding(p)) + boundaryTerm(p); }
    bool contains(const glm::vec3& p, Rule rule) const {
        if (rule == Rule::GeneralizedWinding && caps) return caps->inside(p);
        return insideByRule(winding(p), rule);
    }
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

double ExactClassifier::generalizedWinding(const glm::vec3& p) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->generalizedWinding(p);
}

std::size_t ExactClassifier::boundaryEdgeCount() const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->boundary.size();
}

bool ExactClassifier::contains(const glm::vec3& p, Rule rule) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return impl_->contains(p, rule);
}

bool ExactClassifier::containsByEveryTriangle(const glm::vec3& p, Rule rule) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    const Impl& impl = *impl_;
    const int w = impl.windingBruteForce(p);
    if (rule == Rule::GeneralizedWinding && !impl.boundary.empty())
        return detail::generalizedWindingInside(double(w) + impl.boundaryTerm(p));
    return insideByRule(w, rule);
}

std::size_t ExactClassifier::memoryBytes() const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    const Impl& impl = *impl_;
    // The boundary's caps too: the generalized winding number's queries read them.
    return impl.memoryBytes() + impl.boundary.size() * sizeof(BoundaryEdge) +
           impl.boundaryEnds.size() * sizeof(glm::vec3) + (impl.caps ? impl.caps->memoryBytes() : 0);
}

std::string ExactClassifier::summary() const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    return "exact on " + std::to_string(impl_->tris.size()) + " triangles along " + toString(impl_->axis) +
           (impl_->boundary.empty() ? "" : ", " + windingBoundaryText(impl_->boundary.size()));
}

void ExactClassifier::sweep(const Grid& grid, std::uint8_t* cells, const ClassifyOptions& options) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    if (impl_->axis != Axis::Z) return Classifier::sweep(grid, cells, options);
    // The classifier's own caps: a grid swept in slabs builds them once.
    detail::sweepExact(*impl_, impl_->boundaryEnds, grid, cells, options, detail::SweepWay::Timed,
                       impl_->caps ? &*impl_->caps : nullptr);
}

void ExactClassifier::classifyFloats(const float* xyz, std::size_t count, std::size_t strideBytes, std::uint8_t* labels,
                               const ClassifyOptions& options) const {
    assert(impl_ && "use of a moved-from ExactClassifier");
    assert(strideBytes >= 3 * sizeof(float) && ((xyz && labels) || count == 0));
    const Impl& impl = *impl_;
    const char* base = reinterpret_cast<const char*>(xyz);
    if (options.rule == Rule::GeneralizedWinding && !impl.boundary.empty()) {
        detail::parallelFor(options.threads, count, 4096, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                glm::vec3 p;
                std::memcpy(&p, base + k * strideBytes, sizeof p);
                labels[k] = impl.contains(p, options.rule) ? 1 : 0;
            }
        });
        return;
    }
    // In batches, so that the cache misses of many points overlap: locate a
    // batch and prefetch each point's cell offsets, then read them and
    // prefetch the cell's entries, then count crossings.
    detail::parallelFor(options.threads, count, 4096, [&](std::size_t begin, std::size_t end) {
        constexpr std::size_t kBatch = 16;
        float q[kBatch][3];
        detail::CellGrid::Found found[kBatch];
        for (std::size_t b0 = begin; b0 < end; b0 += kBatch) {
            const std::size_t n = std::min(kBatch, end - b0);
            for (std::size_t i = 0; i < n; ++i) {
                glm::vec3 p;
                std::memcpy(&p, base + (b0 + i) * strideBytes, sizeof p);
                impl.toViewSpace(p, q[i]);
                impl.grid.prefetch(q[i]);
            }
            for (std::size_t i = 0; i < n; ++i) {
                found[i] = impl.grid.find(q[i]);
                if (found[i].begin != found[i].end) __builtin_prefetch(found[i].begin);
            }
            for (std::size_t i = 0; i < n; ++i)
                labels[b0 + i] = insideByRule(impl.winding(found[i], q[i]), options.rule) ? 1 : 0;
        }
    });
}

// ---- The CPU baker --------------------------------------------------------

} // namespace vds
