#include <vds/mesh_check.h>

#include <string>

#include <vds/detail/counted.h>
#include <vds/error.h>

namespace vds {

using detail::counted;

void requireUsable(const MeshReport& report, const std::string& meshName) {
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    if (report.triangleCount == 0) throw InvalidMesh(who + ": empty mesh (no triangles)");
    if (report.nonFiniteVertices)
        throw InvalidMesh(who + ": " + std::to_string(report.nonFiniteVertices) +
                          " vertices have NaN or infinite coordinates");
    if (report.badIndices)
        throw InvalidMesh(who + ": " + std::to_string(report.badIndices) + " triangle indices are out of range");
}

namespace {

/// "open (3 boundary edges, 1 edge shared by an odd number of triangles)".
std::string openFaults(const MeshReport& report) {
    std::string why;
    if (report.boundaryEdges) why = counted(report.boundaryEdges, "boundary edge");
    if (report.oddNonManifoldEdges)
        why += (why.empty() ? "" : ", ") + counted(report.oddNonManifoldEdges, "edge") +
               " shared by an odd number of triangles";
    return "open (" + why + ")";
}

/// " (--rule generalized-winding)", or nothing where the caller has no such flag.
std::string flagText(const std::string& flag) { return flag.empty() ? std::string() : " (" + flag + ")"; }

std::string named(const std::string& meshName) { return meshName.empty() ? std::string("mesh") : meshName; }

} // namespace

std::string openMeshMessage(const MeshReport& report, const std::string& meshName, Rule rule, const MeshFlags& flags) {
    if (rule == Rule::GeneralizedWinding) return {}; // defined for every usable mesh
    const std::string gwn = "the generalized winding number answers for it" + flagText(flags.generalizedWinding);
    if (!report.closed())
        return named(meshName) + " is " + openFaults(report) + ": inside is not defined by the " + toString(rule) +
               " rule; " + gwn +
               (flags.allowOpen.empty() ? std::string()
                                        : ", and answering anyway" + flagText(flags.allowOpen) +
                                              " counts crossings as for a surface, not a solid");
    if (rule == Rule::Winding && !report.oriented())
        return named(meshName) + " has " + counted(report.inconsistentEdges, "inconsistently oriented edge") +
               ": inside is not defined by the winding rule; the parity rule and the generalized winding number" +
               flagText(flags.generalizedWinding) + " answer for it";
    return {};
}

std::string openSpriteMessage(const std::string& validation, Rule rule, const MeshFlags& flags) {
    if (rule == Rule::GeneralizedWinding) return {};
    const bool closed = validation.rfind("closed", 0) == 0; // closed but mis-oriented
    return "the sprite was baked from a mesh that " + std::string(closed ? "is mis-oriented" : "bounds no solid") + " (" +
           validation + "): its " + toString(rule) +
           " answers count crossings as for a surface; the generalized winding number answers for it" +
           flagText(flags.generalizedWinding);
}

std::string misorientedMessage(const MeshReport& report, const std::string& meshName) {
    if (!report.misoriented()) return {};
    std::string what;
    if (report.inconsistentEdges) what = counted(report.inconsistentEdges, "inconsistently oriented edge");
    if (report.insideOutParts)
        what += (what.empty() ? "" : ", ") + counted(report.insideOutParts, "inside-out part");
    const std::string winding = report.inconsistentEdges
                                    ? "the winding rule does not define inside (its counts depend on the ray)"
                                    : "the winding rule counts an inside-out part inside too (winding number -1)";
    // Without a boundary the generalized winding number is the integer count, read as the winding rule reads it.
    const std::string gwn = report.windingBoundaryEdges
                                ? "the generalized winding number sees an inside-out part as outside (near -1)"
                                : "the generalized winding number, an integer here, is read as the winding rule";
    return named(meshName) + " is closed but mis-oriented (" + what +
           "): the parity rule counts crossings and calls a part inside whichever way it faces; " + winding + "; " +
           gwn + "; flip the inward-facing triangles (normals outward) for every rule to agree";
}

void requireVolume(const MeshReport& report, const std::string& meshName) {
    if (!report.flat()) return;
    const std::string who = meshName.empty() ? std::string("mesh") : meshName;
    std::string axes;
    for (int a = 0; a < 3; ++a)
        if (!(report.bounds.hi[a] > report.bounds.lo[a])) axes += std::string(axes.empty() ? "" : " and ") + "xyz"[a];
    const std::string how = axes.empty() ? "all its triangles lie in one plane" : "no extent along " + axes;
    throw InvalidMesh(who + " is flat (" + how +
                      "): it bounds no volume, so no point is inside it by any rule and nothing is baked or written; "
                      "its generalized winding number still measures points off the sheet (between -1/2 and 1/2)");
}

void requireInsideDefined(const MeshReport& report, const std::string& meshName, Rule rule, const MeshFlags& flags) {
    requireUsable(report, meshName);
    const std::string message = openMeshMessage(report, meshName, rule, flags);
    if (!message.empty()) throw InvalidMesh(message);
}

namespace {

std::string nonManifoldText(const MeshReport& report) {
    if (!report.nonManifoldEdges) return {};
    return counted(report.nonManifoldEdges, "non-manifold edge") + " (more than two triangles on an edge)";
}

} // namespace

std::string insideWarning(const MeshReport& report, Rule rule, const MeshFlags& flags) {
    const std::string open = openMeshMessage(report, "the mesh", rule, flags);
    if (!open.empty()) return open + "; answered anyway";
    if (!report.misoriented()) return {};
    const std::string what = nonManifoldText(report);
    return (what.empty() ? "" : what + "; ") + misorientedMessage(report, "the mesh");
}

std::string insideNote(const MeshReport& report, Rule rule, const MeshFlags& flags) {
    if (!insideWarning(report, rule, flags).empty()) return {}; // the warning says it
    const std::string what = nonManifoldText(report);
    if (what.empty()) return what;
    return what + "; inside is still defined by the " + toString(rule) + " rule";
}

} // namespace vds
