#include <vds/mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <unordered_map>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/sprite.h>

namespace vds {
namespace {

struct PositionHash {
    std::size_t operator()(const glm::vec3& p) const {
        std::uint32_t b[3];
        std::memcpy(b, &p, sizeof b);
        std::uint64_t h = 1469598103934665603ull;
        for (std::uint32_t v : b) h = (h ^ v) * 1099511628211ull;
        return static_cast<std::size_t>(h);
    }
};
struct PositionEqual {
    bool operator()(const glm::vec3& a, const glm::vec3& b) const { return std::memcmp(&a, &b, sizeof a) == 0; }
};

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

/// "1 boundary edge", "3 boundary edges".
std::string counted(std::size_t n, const char* one, const char* many = nullptr) {
    return std::to_string(n) + " " + (n == 1 ? one : many ? many : std::string(one) + "s");
}

} // namespace

std::string MeshReport::summary() const {
    if (triangleCount == 0) return "empty: no triangles";
    std::ostringstream s;
    if (nonFiniteVertices) s << "non-finite: " << nonFiniteVertices << " vertices with NaN or infinite coordinates, ";
    if (badIndices) s << "invalid: " << badIndices << " indices out of range, ";
    s << (closed() ? "closed" : "open");
    if (!closed()) {
        s << " (";
        if (boundaryEdges) s << counted(boundaryEdges, "boundary edge") << (oddNonManifoldEdges ? ", " : "");
        if (oddNonManifoldEdges) s << counted(oddNonManifoldEdges, "edge") << " shared by an odd number of triangles";
        s << ")";
    }
    if (nonManifoldEdges) s << ", " << counted(nonManifoldEdges, "non-manifold edge");
    if (inconsistentEdges) s << ", " << counted(inconsistentEdges, "inconsistently oriented edge");
    s << ", " << counted(triangleCount, "triangle") << ", " << counted(vertexCount, "vertex", "vertices");
    if (degenerateTriangles) s << ", " << counted(degenerateTriangles, "degenerate triangle");
    if (duplicateTriangles) s << ", " << counted(duplicateTriangles, "duplicate triangle");
    if (isolatedVertices) s << ", " << counted(isolatedVertices, "isolated vertex", "isolated vertices");
    return s.str();
}

MeshReport validateMesh(MeshView mesh) {
    MeshReport r;
    r.vertexCount = mesh.positionCount;
    r.triangleCount = mesh.triangleCount;
    for (std::size_t i = 0; i < mesh.positionCount; ++i)
        if (!finite(mesh.positions[i])) ++r.nonFiniteVertices;

    // Weld by exact position so duplicated vertices still share edges.
    std::vector<std::uint32_t> weld(mesh.positionCount);
    {
        std::unordered_map<glm::vec3, std::uint32_t, PositionHash, PositionEqual> first;
        first.reserve(mesh.positionCount);
        for (std::size_t i = 0; i < mesh.positionCount; ++i)
            weld[i] = first.emplace(mesh.positions[i], static_cast<std::uint32_t>(i)).first->second;
    }

    // Directed edges (a, b) packed in 64 bits; sorted, then counted per
    // undirected edge. Welded vertex triples, sorted, find duplicate triangles.
    std::vector<std::uint64_t> directed;
    directed.reserve(mesh.triangleCount * 3);
    std::vector<std::array<std::uint32_t, 3>> corners;
    corners.reserve(mesh.triangleCount);
    std::vector<bool> used(mesh.positionCount, false);
    bool anyBounds = false;
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= mesh.positionCount || tri.y >= mesh.positionCount || tri.z >= mesh.positionCount) {
            ++r.badIndices;
            continue;
        }
        const std::uint32_t w[3] = {weld[tri.x], weld[tri.y], weld[tri.z]};
        for (std::uint32_t v : w) used[v] = true;
        const glm::vec3 &a = mesh.positions[tri.x], &b = mesh.positions[tri.y], &c = mesh.positions[tri.z];
        for (const glm::vec3* p : {&a, &b, &c})
            if (finite(*p)) {
                if (!anyBounds) { r.bounds.lo = r.bounds.hi = *p; anyBounds = true; }
                r.bounds.lo = glm::min(r.bounds.lo, *p);
                r.bounds.hi = glm::max(r.bounds.hi, *p);
            }
        if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || glm::length(glm::cross(b - a, c - a)) == 0.0f) {
            ++r.degenerateTriangles;
            if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue; // edges of a collapsed triangle mean nothing
        }
        std::array<std::uint32_t, 3> sorted = {w[0], w[1], w[2]};
        std::sort(sorted.begin(), sorted.end());
        corners.push_back(sorted);
        for (int k = 0; k < 3; ++k)
            directed.push_back((std::uint64_t(w[k]) << 32) | w[(k + 1) % 3]);
    }
    for (std::size_t i = 0; i < mesh.positionCount; ++i)
        if (!used[weld[i]]) ++r.isolatedVertices;
    std::sort(corners.begin(), corners.end());
    for (std::size_t i = 1; i < corners.size(); ++i)
        if (corners[i] == corners[i - 1]) ++r.duplicateTriangles;

    // Undirected key (lower index first) and whether this use runs lower -> higher.
    std::vector<std::pair<std::uint64_t, bool>> edges;
    edges.reserve(directed.size());
    for (std::uint64_t e : directed) {
        const std::uint32_t a = std::uint32_t(e >> 32), b = std::uint32_t(e);
        edges.emplace_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), a < b);
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i, forward = 0;
        while (j < edges.size() && edges[j].first == edges[i].first) forward += edges[j++].second;
        const std::size_t uses = j - i;
        if (uses == 1) ++r.boundaryEdges;
        if (uses > 2) ++r.nonManifoldEdges;
        if (uses > 2 && uses % 2 == 1) ++r.oddNonManifoldEdges;
        if (uses % 2 == 0 && 2 * forward != uses) ++r.inconsistentEdges;
        i = j;
    }
    return r;
}

void requireUsable(const MeshReport& report, const std::string& meshName) {
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    if (report.triangleCount == 0) throw InvalidMesh(who + ": empty mesh (no triangles)");
    if (report.nonFiniteVertices)
        throw InvalidMesh(who + ": " + std::to_string(report.nonFiniteVertices) +
                          " vertices have NaN or infinite coordinates");
    if (report.badIndices)
        throw InvalidMesh(who + ": " + std::to_string(report.badIndices) + " triangle indices are out of range");
}

void requireInsideDefined(const MeshReport& report, const std::string& meshName, Rule rule) {
    requireUsable(report, meshName);
    if (rule == Rule::GeneralizedWinding) return; // defined for every usable mesh
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    if (!report.closed()) {
        std::string why;
        if (report.boundaryEdges) why = counted(report.boundaryEdges, "boundary edge");
        if (report.oddNonManifoldEdges)
            why += (why.empty() ? "" : ", ") + counted(report.oddNonManifoldEdges, "edge") +
                   " shared by an odd number of triangles";
        throw InvalidMesh(who + " is open (" + why + "): inside is not defined by the " + toString(rule) +
                          " rule; the generalized-winding rule answers for it (exactly), and a sprite baked from it "
                          "still answers by crossing count");
    }
    if (rule == Rule::Winding && !report.oriented())
        throw InvalidMesh(who + " has " + counted(report.inconsistentEdges, "inconsistently oriented edge") +
                          ": inside is not defined by the winding rule; the parity rule defines it");
}

std::string insideWarning(const MeshReport& report, Rule rule) {
    std::string what;
    if (report.nonManifoldEdges)
        what = counted(report.nonManifoldEdges, "non-manifold edge") + " (more than two triangles on an edge)";
    if (rule == Rule::Parity && report.inconsistentEdges)
        what += (what.empty() ? "" : ", ") + counted(report.inconsistentEdges, "inconsistently oriented edge");
    if (what.empty()) return what;
    return what + "; inside is still defined by the " + toString(rule) + " rule";
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
