// vds._vds: numpy arrays and Python arguments as the library's plain data —
// points as a PointsView, (V, F) as a MeshView (in place where the layout
// allows), grids, thread counts and paths — with one rule for refusals:
// a wrong dtype raises `DTypeError` (vds.DTypeError, a TypeError and a
// vds.InvalidArgument), a wrong shape or value `vds::InvalidArgument`, bad
// faces `vds::InvalidMesh`; numbers are taken as Python objects and judged
// here, so a wrong one never meets pybind11's conversion error (which
// prints every argument, arrays included).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <glm/vec3.hpp>

#include <vds/classify.h>
#include <vds/error.h>
#include <vds/grid.h>
#include <vds/mesh.h>

namespace vds::python {

namespace py = pybind11;

/// An array of the wrong element type (points that are not floats, faces that
/// are not integers). Raised in Python as vds.DTypeError.
class DTypeError : public InvalidArgument {
public:
    using InvalidArgument::InvalidArgument;
};

/// "(4, 2)": an array's shape as numpy prints it.
std::string shapeText(const py::array& a);

/// An (N, 3) array of points as the library reads them: `view()` is the
/// caller's own memory where it holds native float32 or float64 with x, y, z
/// adjacent (any row stride, negative ones included), else `packed`. Made
/// with the GIL by `viewPoints`; `prepare` runs without it.
struct Points {
    py::array source; ///< keeps the caller's array alive
    const char* data = nullptr;
    py::ssize_t rowStride = 0, columnStride = 0;
    bool isDouble = false;
    std::size_t count = 0;
    std::vector<glm::vec3> packed;
    PointsView points;

    /// Checks every coordinate (a non-finite one, or a float64 beyond
    /// float's range, throws `InvalidArgument` naming the row) and sets
    /// `points`. `packedNeeded`: the caller needs packed glm::vec3 rows.
    void prepare(bool packedNeeded, const char* what = "points");
    const glm::vec3* vec3() const { return static_cast<const glm::vec3*>(points.data); }

private:
    double at(std::size_t row, int column) const;
};

/// `object` as points: float32 or float64 (either byte order), shape (N, 3).
/// Anything else is refused (`DTypeError` for the dtype, `InvalidArgument`
/// for the shape); lists are read by numpy first.
Points viewPoints(const py::object& object, const char* what = "points");

/// V (n, 3) and F (m, 3) as a MeshView: float32 C-contiguous V and int32 or
/// uint32 C-contiguous F (native byte order) are viewed in place, anything
/// else is copied once into `positions` / `triangles`. V must hold floats,
/// F integers (`DTypeError` otherwise); every index is checked against n
/// (`InvalidMesh` names the first bad one). Keep the object alive while the
/// view is used; the GIL may be released meanwhile.
struct MeshArrays {
    py::array vertices, faces; ///< keep the caller's arrays alive
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    MeshView view;
    bool verticesCopied = false, facesCopied = false;
};
MeshArrays meshArrays(const py::object& vertices, const py::object& faces);

/// A thread count: a non-negative integer (0: one per hardware thread), else
/// `InvalidArgument` naming what was given.
unsigned threadCount(const py::object& threads, const char* what = "threads");
/// A count option (resolution, slices, cells): an integer in [0, 2^32), else
/// `InvalidArgument` naming `what` and what was given. The library judges its range.
std::uint32_t countOption(const py::object& value, const char* what);

/// The name of `value`'s type ("str", "tuple"), for messages.
std::string typeName(const py::handle& value);
/// A text option (rule, axis, method): a str, else `DTypeError` (a
/// vds.Error and a TypeError) naming `what` and the type given.
std::string textOption(const py::object& value, const char* what);

/// A path as the bytes the file system sees: str, bytes or os.PathLike.
std::string fsPath(const py::object& path);
/// Throws `IoError` when `path` names a directory (a file was expected).
void requireNotDirectory(const std::string& path);

/// Three floats from a sequence (a box corner).
glm::vec3 vec3From(const py::object& object, const char* what);
/// Three positive cell counts: an int (the same along x, y, z) or three ints.
glm::uvec3 dimsFrom(const py::object& object);

/// A new bool array of `grid`'s shape (dims.x, dims.y, dims.z), C order:
/// element [i, j, k] is byte `grid.index(i, j, k)`.
py::array_t<bool> gridArray(const Grid& grid);

} // namespace vds::python
