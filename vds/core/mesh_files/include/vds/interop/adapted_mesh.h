// vds: a mesh view made from another library's mesh, copying only what
// cannot be viewed in place. The adapters (<vds/interop/eigen.h>,
// <vds/interop/openmesh.h>; numpy arrays in Python) return one:
//
//   const vds::AdaptedMesh mesh = vds::fromEigen(V, F); // libigl's (V, F)
//   vds::ExactClassifier exact(mesh);                   // a MeshView
//
// Header-only: vds is built without Eigen or OpenMesh; a program that
// includes an adapter brings its own.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <vds/mesh.h>

namespace vds {

/// A `MeshView` of another library's arrays, or of a copy made from them
/// (positions and triangles each viewed in place where their layout is
/// vds's own: 3 packed floats, 3 packed 32-bit indices). Moving it keeps
/// the view valid; it must not outlive arrays it views in place.
class AdaptedMesh {
public:
    AdaptedMesh() = default;
    AdaptedMesh(const AdaptedMesh&) = delete;
    AdaptedMesh& operator=(const AdaptedMesh&) = delete;
    AdaptedMesh(AdaptedMesh&& other) noexcept { *this = std::move(other); }
    AdaptedMesh& operator=(AdaptedMesh&& other) noexcept {
        copy_ = std::move(other.copy_);
        positionsCopied_ = other.positionsCopied_;
        trianglesCopied_ = other.trianglesCopied_;
        view_ = other.view_;
        if (positionsCopied_) view_.positions = copy_.positions.data();
        if (trianglesCopied_) view_.triangles = copy_.triangles.data();
        return *this;
    }

    /// Views `positions` and `triangles` as they are (no copy).
    static AdaptedMesh viewing(const glm::vec3* positions, std::size_t positionCount, const glm::uvec3* triangles,
                               std::size_t triangleCount) {
        AdaptedMesh m;
        m.view_ = MeshView(positions, positionCount, triangles, triangleCount);
        return m;
    }
    /// Sets the positions to a copy (filled by the adapter).
    std::vector<glm::vec3>& copyPositions(std::size_t count) {
        copy_.positions.resize(count);
        positionsCopied_ = true;
        view_.positions = copy_.positions.data();
        view_.positionCount = count;
        return copy_.positions;
    }
    /// Sets the triangles to a copy (filled by the adapter).
    std::vector<glm::uvec3>& copyTriangles(std::size_t count) {
        copy_.triangles.resize(count);
        trianglesCopied_ = true;
        view_.triangles = copy_.triangles.data();
        view_.triangleCount = count;
        return copy_.triangles;
    }
    void viewPositions(const glm::vec3* positions, std::size_t count) {
        view_.positions = positions;
        view_.positionCount = count;
    }
    void viewTriangles(const glm::uvec3* triangles, std::size_t count) {
        view_.triangles = triangles;
        view_.triangleCount = count;
    }

    const MeshView& view() const { return view_; }
    operator MeshView() const { return view_; } // NOLINT: implicit on purpose, it is a view
    /// True where that array is a copy.
    bool positionsCopied() const { return positionsCopied_; }
    bool trianglesCopied() const { return trianglesCopied_; }

private:
    TriangleMesh copy_;
    bool positionsCopied_ = false;
    bool trianglesCopied_ = false;
    MeshView view_;
};

} // namespace vds
