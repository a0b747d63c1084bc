// vds: the boundary term of the generalized winding number by capping the
// boundary loops (boundary_caps.h); the Antipodal split is Martens,
// Trettner & Bessmeltsev 2026, the tree expansion Barill, Dickson, Schmidt,
// Levin & Jacobson 2018, section 3.
#include <vds/detail/boundary_caps.h>

namespace vds::detail {

namespace {
EdgeTree edgeTreeOf(const CapLoops& loops) {
    EdgeTree tree;
    tree.build(loops.edges(), loops.loopEdges(), loops.loops(), loops.closed());
    return tree;
}
} // namespace

BoundaryCaps::BoundaryCaps(const glm::vec3* edges, std::size_t edgeCount, Axis axis, const Box* domain,
                           const CapsSurface* surface, const CellWindings* windings)
    : loops_(edges, edgeCount, axis), edgeTree_(edgeTreeOf(loops_)), labels_(loops_), values_(loops_),
      ranges_(loops_, values_, labels_, edgeTree_, domain, surface, windings) {}

double BoundaryCaps::generalizedWinding(int winding, const glm::vec3& q, double tolerance) const {
    const Estimate e = values_.estimate(q, kCapValueTolerance);
    return e.bound <= tolerance ? double(winding) + e.term : loops_.exact(winding, q);
}

std::size_t BoundaryCaps::memoryBytes() const {
    return loops_.memoryBytes() + edgeTree_.memoryBytes() + labels_.memoryBytes() + values_.memoryBytes() +
           ranges_.memoryBytes();
}

} // namespace vds::detail
