// vds: meshes from Eigen matrices, as libigl holds them: V (n x 3 vertex
// positions, any scalar) and F (m x 3 vertex indices, any integer type).
// Header-only; include Eigen before or through this header.
//
//   Eigen::MatrixXd V; Eigen::MatrixXi F;            // igl::read_triangle_mesh(path, V, F)
//   const vds::AdaptedMesh mesh = vds::fromEigen(V, F);
//
// Viewed in place when V is row-major float with 3 columns and F row-major
// with 32-bit indices and 3 columns, both with contiguous rows
// (`Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>` and the like);
// copied otherwise (libigl's default column-major double V is copied, and
// rounded to float, which every vds method works in).
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>

#include <Eigen/Core>

#include <vds/error.h>
#include <vds/interop/adapted_mesh.h>

namespace vds {

/// Throws `InvalidMesh` when V or F does not have 3 columns, or when an
/// index is negative or does not fit 32 bits (indices past V's rows are left
/// to mesh validation, which names them).
template <class DerivedV, class DerivedF>
AdaptedMesh fromEigen(const Eigen::MatrixBase<DerivedV>& V, const Eigen::MatrixBase<DerivedF>& F) {
    using ScalarV = typename DerivedV::Scalar;
    using ScalarF = typename DerivedF::Scalar;
    static_assert(std::is_floating_point<ScalarV>::value, "vds::fromEigen: V must hold floating-point positions");
    static_assert(std::is_integral<ScalarF>::value, "vds::fromEigen: F must hold integer vertex indices");
    if (V.cols() != 3 || F.cols() != 3)
        throw InvalidMesh("vds::fromEigen: V and F need 3 columns (got V " + std::to_string(V.rows()) + " x " +
                          std::to_string(V.cols()) + ", F " + std::to_string(F.rows()) + " x " +
                          std::to_string(F.cols()) + ")");
    AdaptedMesh mesh;
    const std::size_t nv = std::size_t(V.rows()), nf = std::size_t(F.rows());
    const auto& v = V.derived();
    const auto& f = F.derived();
    // In place: packed rows of three floats / three 32-bit indices.
    constexpr bool vRowMajor = bool(DerivedV::Flags & Eigen::RowMajorBit);
    constexpr bool fRowMajor = bool(DerivedF::Flags & Eigen::RowMajorBit);
    constexpr bool vDirect = bool(DerivedV::Flags & Eigen::DirectAccessBit);
    constexpr bool fDirect = bool(DerivedF::Flags & Eigen::DirectAccessBit);
    if constexpr (std::is_same<ScalarV, float>::value && vRowMajor && vDirect) {
        if (v.innerStride() == 1 && (nv < 2 || v.outerStride() == 3)) {
            mesh.viewPositions(reinterpret_cast<const glm::vec3*>(v.data()), nv);
        }
    }
    if (nv && !mesh.view().positions) {
        std::vector<glm::vec3>& p = mesh.copyPositions(nv);
        for (std::size_t i = 0; i < nv; ++i)
            p[i] = glm::vec3(float(v(Eigen::Index(i), 0)), float(v(Eigen::Index(i), 1)), float(v(Eigen::Index(i), 2)));
    }
    if constexpr (sizeof(ScalarF) == 4 && fRowMajor && fDirect) {
        bool fits = f.innerStride() == 1 && (nf < 2 || f.outerStride() == 3);
        if constexpr (std::is_signed<ScalarF>::value)
            for (std::size_t i = 0; fits && i < nf; ++i)
                fits = f(Eigen::Index(i), 0) >= 0 && f(Eigen::Index(i), 1) >= 0 && f(Eigen::Index(i), 2) >= 0;
        if (fits) mesh.viewTriangles(reinterpret_cast<const glm::uvec3*>(f.data()), nf);
    }
    if (nf && !mesh.view().triangles) {
        std::vector<glm::uvec3>& t = mesh.copyTriangles(nf);
        for (std::size_t i = 0; i < nf; ++i)
            for (int c = 0; c < 3; ++c) {
                const auto index = f(Eigen::Index(i), c);
                if (index < 0 || std::uint64_t(index) > 0xffffffffull)
                    throw InvalidMesh("vds::fromEigen: F(" + std::to_string(i) + ", " + std::to_string(c) + ") = " +
                                      std::to_string(index) + " is not a vertex index");
                t[i][c] = std::uint32_t(index);
            }
    }
    return mesh;
}

} // namespace vds
