#include <vds/mesh.h>

#include <sstream>
#include <vector>

#include <glm/common.hpp>

#include <vds/detail/counted.h>

namespace vds {

using detail::counted;

std::string windingBoundaryText(std::size_t edges) {
    return counted(edges, "edge") + " in the generalized winding number's boundary";
}

std::string MeshReport::summary() const {
    if (triangleCount == 0)
        return "empty: no triangles" +
               (skippedFaces ? " (" + counted(skippedFaces, "face") + " of fewer than 3 vertices skipped)" : "");
    std::ostringstream s;
    if (nonFiniteVertices) s << "non-finite: " << nonFiniteVertices << " vertices with NaN or infinite coordinates, ";
    if (badIndices) s << "invalid: " << badIndices << " indices out of range, ";
    std::vector<std::string> faults;
    if (boundaryEdges) faults.push_back(counted(boundaryEdges, "boundary edge"));
    if (oddNonManifoldEdges) faults.push_back(counted(oddNonManifoldEdges, "edge") + " shared by an odd number of triangles");
    if (closed() && inconsistentEdges) faults.push_back(counted(inconsistentEdges, "inconsistently oriented edge"));
    if (insideOutParts) faults.push_back(counted(insideOutParts, "inside-out part"));
    s << (!closed() ? "open" : misoriented() ? "closed but mis-oriented" : "closed");
    if (!faults.empty()) {
        s << " (";
        for (std::size_t k = 0; k < faults.size(); ++k) s << (k ? ", " : "") << faults[k];
        // The generalized winding number's count, where it is not the boundary edges' own.
        if (windingBoundaryEdges != boundaryEdges) s << "; " << windingBoundaryText(windingBoundaryEdges);
        s << ")";
    }
    if (nonManifoldEdges) s << ", " << counted(nonManifoldEdges, "non-manifold edge");
    if (!closed() && inconsistentEdges) s << ", " << counted(inconsistentEdges, "inconsistently oriented edge");
    s << ", " << counted(triangleCount, "triangle") << ", " << counted(vertexCount, "vertex", "vertices");
    if (degenerateTriangles) s << ", " << counted(degenerateTriangles, "degenerate triangle");
    if (duplicateTriangles) s << ", " << counted(duplicateTriangles, "duplicate triangle");
    if (isolatedVertices) s << ", " << counted(isolatedVertices, "isolated vertex", "isolated vertices");
    if (skippedFaces) s << ", " << counted(skippedFaces, "face") << " of fewer than 3 vertices skipped";
    return s.str();
}


bool MeshReport::flat() const {
    for (int a = 0; a < 3; ++a)
        if (!(bounds.hi[a] > bounds.lo[a])) return true;
    return coplanar;
}


Box meshBounds(MeshView mesh) {
    Box b;
    bool any = false;
    for (std::size_t t = 0; t < mesh.triangleCount; ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = mesh.triangles[t][k];
            if (i >= mesh.positionCount) continue;
            const glm::vec3& p = mesh.positions[i];
            if (!any) { b.lo = b.hi = p; any = true; }
            b.lo = glm::min(b.lo, p);
            b.hi = glm::max(b.hi, p);
        }
    return b;
}

} // namespace vds
