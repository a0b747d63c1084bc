// vds: checking a mesh before it is answered: validation (welded by
// position, its edges grouped, its parts' orientation summed) into a
// `MeshReport` (<vds/mesh.h>), and the one wording of what the report means
// for each rule, shared by the C++ API, the vds tool and Python.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <vds/mesh.h>
#include <vds/rule.h>

namespace vds {

/// Validates a mesh. Time linear in the vertex and triangle counts (but for
/// vertices of very high valence); memory about 50 bytes per triangle and
/// 20 + 8 per thread per vertex. Runs on up to `threads` threads (0: one per
/// hardware thread), at most 8, one more per 64k triangles. Thread-safe;
/// never throws for bad geometry (it counts it), only for allocation failure.
MeshReport validateMesh(MeshView mesh, unsigned threads = 0);

/// Throws `InvalidMesh` with a one-line reason if `report` is not `usable()`.
void requireUsable(const MeshReport& report, const std::string& meshName);

/// How a caller spells the flags its messages name: asking for the
/// generalized winding number, and answering a mesh that bounds no solid
/// anyway. Empty: the caller has no such flag, and no message names one.
struct MeshFlags {
    std::string generalizedWinding; ///< e.g. "--rule generalized-winding" (the vds tool)
    std::string allowOpen;          ///< e.g. "--allow-open" (vds classify); empty: answering anyway is not offered
};

/// Throws `InvalidMesh` unless the mesh is usable and `rule` defines inside
/// for it (see `MeshReport`): `closed()` for `Rule::Parity`, `oriented()`
/// for `Rule::Winding`, any usable mesh for `Rule::GeneralizedWinding`. The
/// one-line message is `openMeshMessage`'s.
void requireInsideDefined(const MeshReport& report, const std::string& meshName, Rule rule,
                          const MeshFlags& flags = {});
/// The one wording (CLI, Python, C++) for a mesh whose inside `rule` does
/// not define (open; or inconsistently oriented, for the winding rule):
/// what the mesh is, the rule that answers for it (generalized-winding),
/// and, where `flags.allowOpen` names a flag, what answering anyway gives.
/// Empty where `rule` defines inside.
std::string openMeshMessage(const MeshReport& report, const std::string& meshName, Rule rule,
                            const MeshFlags& flags = {});
/// The same for a sprite baked from such a mesh (its `Sprite::validation`
/// summary), asked by `rule`; empty for Rule::GeneralizedWinding.
std::string openSpriteMessage(const std::string& validation, Rule rule, const MeshFlags& flags = {});
/// The one wording for a closed but mis-oriented mesh (`misoriented()`):
/// what is wrong, what each rule answers (parity and winding count
/// crossings, the generalized winding number sees an inside-out part as
/// outside) and the fix. Empty for any other mesh.
std::string misorientedMessage(const MeshReport& report, const std::string& meshName);
/// Throws `InvalidMesh` with the one wording for a flat mesh (`flat()`):
/// it bounds no volume, what can still be asked of it. Every command that
/// needs a volume (bake, classify, voxelize, compare) calls it first.
void requireVolume(const MeshReport& report, const std::string& meshName);

/// What a caller should warn about in a mesh asked by `rule`: where `rule`
/// does not define inside (a caller answering anyway), `openMeshMessage`'s
/// text; else a closed mesh's mis-orientation (`misorientedMessage`, after
/// its non-manifold edges, if any). Empty when there is nothing to warn of.
std::string insideWarning(const MeshReport& report, Rule rule, const MeshFlags& flags = {});

/// What is worth telling, not warning, of a mesh whose inside `rule` does
/// define: its non-manifold edges (named with their count; inside is still
/// defined). Empty where there is nothing to tell, or `insideWarning` has
/// something to say.
std::string insideNote(const MeshReport& report, Rule rule, const MeshFlags& flags = {});

/// Validation that keeps what it found beside the report: the partners of
/// the mesh's edges and its triangles' facings, which the axis choice
/// (`chooseViewAxis` in <vds/bake.h>) and the bakes would otherwise find
/// again. The mesh must outlive it only as long as the view is used by
/// those calls; it holds no pointer into the mesh. Move-only.
class MeshValidation {
public:
    /// `validateMesh(mesh, threads)`, keeping its finds.
    explicit MeshValidation(MeshView mesh, unsigned threads = 0);
    ~MeshValidation();
    MeshValidation(MeshValidation&&) noexcept;
    MeshValidation& operator=(MeshValidation&&) noexcept;

    const MeshReport& report() const { return report_; }

    /// What validation found beyond the report (defined inside the library).
    struct Finds;
    const Finds& finds() const { return *finds_; }

private:
    MeshReport report_;
    std::unique_ptr<Finds> finds_;
};

} // namespace vds
