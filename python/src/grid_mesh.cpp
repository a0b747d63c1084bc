// vds.Grid and the functions on meshes (load_mesh, validate_mesh, occupancy).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vds/all.h>
#include <vds/error.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include <vds/sample.h>
#include <vds/vds_file.h>

#include "arrays.h"
#include "bindings.h"

namespace py = pybind11;
using vds::python::DTypeError;
using vds::python::MeshArrays;
using vds::python::Points;

namespace vds::python {

py::tuple tuple3(const glm::vec3& v) { return py::make_tuple(double(v.x), double(v.y), double(v.z)); }

vds::Grid gridFrom(const py::object& grid) {
    if (!py::isinstance<vds::Grid>(grid))
        throw DTypeError("grid must be a vds.Grid (vds.Grid(lo, hi, dims)), not " + typeName(grid));
    return grid.cast<vds::Grid>();
}

py::tuple MeshCopy::arrays() const {
    py::array_t<float> v({py::ssize_t(positions.size()), py::ssize_t(3)});
    py::array_t<std::uint32_t> f({py::ssize_t(triangles.size()), py::ssize_t(3)});
    if (!positions.empty()) std::memcpy(v.mutable_data(), positions.data(), positions.size() * sizeof(glm::vec3));
    if (!triangles.empty()) std::memcpy(f.mutable_data(), triangles.data(), triangles.size() * sizeof(glm::uvec3));
    return py::make_tuple(v, f);
}

namespace {

// ---- meshes ----------------------------------------------------------------

py::tuple meshArraysOut(const vds::TriangleMesh& mesh) {
    py::array_t<double> v({py::ssize_t(mesh.positions.size()), py::ssize_t(3)});
    py::array_t<std::int32_t> f({py::ssize_t(mesh.triangles.size()), py::ssize_t(3)});
    auto vv = v.mutable_unchecked<2>();
    auto ff = f.mutable_unchecked<2>();
    for (std::size_t k = 0; k < mesh.positions.size(); ++k)
        for (int c = 0; c < 3; ++c) vv(py::ssize_t(k), c) = mesh.positions[k][c];
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
        for (int c = 0; c < 3; ++c) ff(py::ssize_t(k), c) = std::int32_t(mesh.triangles[k][c]);
    return py::make_tuple(v, f);
}

/// vds.occupancy(V, F, grid): the exact sweep on the triangles.
BoolArray meshOccupancy(const py::object& vertices, const py::object& faces, const py::object& gridObject,
                        const py::object& rule, const py::object& threads) {
    const vds::Grid grid = gridFrom(gridObject);
    const vds::ClassifyOptions options = classifyOptions(rule, threads);
    const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
    vds::MeshReport report;
    {
        py::gil_scoped_release released;
        report = vds::validateMesh(mesh.view);
    }
    vds::requireUsable(report, "");
    warn(insideMessage(report, "", options.rule));
    BoolArray cells = vds::python::gridArray(grid);
    auto* out = reinterpret_cast<std::uint8_t*>(cells.mutable_data());
    py::gil_scoped_release released;
    vds::occupancy(mesh.view, grid, out, options);
    return cells;
}

// ---- grids -----------------------------------------------------------------

/// Three cell indices >= 0 (a block's first cell).
glm::uvec3 firstFrom(const py::object& object) {
    const auto bad = [&] {
        throw vds::InvalidArgument("grid first must be three cell indices >= 0 (i, j, k), not " +
                                   py::repr(object).cast<std::string>());
    };
    const py::object list = py::isinstance<py::array>(object) ? object.attr("tolist")() : object;
    if (!py::isinstance<py::sequence>(list) || py::isinstance<py::str>(list) || py::len(list) != 3) bad();
    const py::object index = py::module_::import("operator").attr("index");
    glm::uvec3 first(0u);
    for (int a = 0; a < 3; ++a) {
        long long value = -1;
        try {
            value = index(list[py::int_(a)]).cast<long long>();
        } catch (const std::exception&) { // not an integer, or beyond long long
        }
        if (value < 0 || value > 0xffffffffLL) bad();
        first[a] = std::uint32_t(value);
    }
    return first;
}

/// Grid(lo, hi, dims) or, with `whole`, the block of `dims` cells from cell
/// `first` of the grid of `whole` cells over [lo, hi].
vds::Grid makeGrid(const py::object& lo, const py::object& hi, const py::object& dims, const py::object& first,
                   const py::object& whole) {
    vds::Grid grid;
    grid.box.lo = vds::python::vec3From(lo, "lo");
    grid.box.hi = vds::python::vec3From(hi, "hi");
    grid.dims = vds::python::dimsFrom(dims);
    if (!whole.is_none()) {
        grid.whole = vds::python::dimsFrom(whole);
        grid.first = firstFrom(first);
    } else if (!first.is_none() && firstFrom(first) != glm::uvec3(0u)) {
        throw vds::InvalidArgument("grid first needs whole: the cell counts of the grid the block is part of");
    }
    vds::checkGrid(grid);
    return grid;
}

py::tuple dims3(const glm::uvec3& d) { return py::make_tuple(d.x, d.y, d.z); }

/// A block's whole-grid cells, or None for a grid that is whole.
py::object wholeOf(const vds::Grid& g) {
    if (g.whole == glm::uvec3(0u)) return py::none();
    return dims3(glm::uvec3(g.wholeCells(0), g.wholeCells(1), g.wholeCells(2)));
}


py::array_t<float> cellCentres(const vds::Grid& grid) {
    py::array_t<float> c({py::ssize_t(grid.dims.x), py::ssize_t(grid.dims.y), py::ssize_t(grid.dims.z), py::ssize_t(3)});
    auto* out = reinterpret_cast<glm::vec3*>(c.mutable_data());
    py::gil_scoped_release released;
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) out[grid.index(i, j, k)] = grid.cellCentre(i, j, k);
    return c;
}

} // namespace

void bindGrid(py::module_& m) {
    py::class_<vds::Grid>(m, "Grid", R"doc(
A regular grid of cells over a box, the one grid of every occupancy call:
Grid(lo, hi, dims), lo and hi the box's corners (x, y, z; stored as float32,
as the C++ vds::Grid), dims one cell count for all three axes or (nx, ny, nz).

Cell (i, j, k) has the centre lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / dims,
evaluated in float64 and rounded to float32 (`cell_centres`). Occupancy
arrays have the shape (nx, ny, nz), C order, indexed [i, j, k] (x slowest,
z fastest), as the C++ `Grid::index`. Raises vds.InvalidArgument for a zero
dimension, more than 2^34 cells, or a box that is empty or not finite.

Grid(lo, hi, dims, first=(i, j, k), whole=(NX, NY, NZ)) is a block of a
larger grid: its cell (a, b, c) is cell first + (a, b, c) of the grid of
`whole` cells over [lo, hi], with that cell's centre exactly, so a grid is
labelled block by block (vds.dask) with the labels of one call. Only the
block's own cells count against the 2^34 limit; first + dims must lie
within whole.)doc")
        .def(py::init(&makeGrid), py::arg("lo"), py::arg("hi"), py::arg("dims"), py::kw_only(),
             py::arg("first") = py::none(), py::arg("whole") = py::none())
        .def_static("cubic", [](const py::object& lo, const py::object& hi, const py::object& n) {
                 vds::Box box{vds::python::vec3From(lo, "lo"), vds::python::vec3From(hi, "hi")};
                 const std::uint32_t cells = vds::python::countOption(n, "n");
                 if (cells == 0) throw vds::InvalidArgument("n must be a positive cell count, not 0");
                 vds::Grid grid = vds::cubicGrid(box, cells);
                 vds::checkGrid(grid);
                 return grid;
             }, py::arg("lo"), py::arg("hi"), py::arg("n"),
             "n cubic cells along the box's longest side and as many as fit along the others (at least 1); "
             "hi grows to whole cells.")
        .def_property_readonly("lo", [](const vds::Grid& g) { return tuple3(g.box.lo); }, "(x, y, z), float32 values")
        .def_property_readonly("hi", [](const vds::Grid& g) { return tuple3(g.box.hi); }, "(x, y, z), float32 values")
        .def_property_readonly("dims", [](const vds::Grid& g) { return py::make_tuple(g.dims.x, g.dims.y, g.dims.z); },
                               "(nx, ny, nz)")
        .def_property_readonly("shape", [](const vds::Grid& g) { return py::make_tuple(g.dims.x, g.dims.y, g.dims.z); },
                               "the shape of occupancy arrays: (nx, ny, nz)")
        .def_property_readonly("spacing", [](const vds::Grid& g) {
                 const auto step = [&](int a) {
                     return (double(g.box.hi[a]) - double(g.box.lo[a])) / double(g.wholeCells(a));
                 };
                 return py::make_tuple(step(0), step(1), step(2));
             }, "(dx, dy, dz) float64: the cells' edges, (hi - lo) / cells of the whole grid; cell [i, j, k]'s centre "
                "is lo + (first + (i, j, k) + 1/2) * spacing, rounded to float32")
        .def_property_readonly("cell_count", &vds::Grid::cellCount)
        .def_property_readonly("first", [](const vds::Grid& g) { return dims3(g.first); },
                               "a block's first cell in its whole grid; (0, 0, 0) for a whole grid")
        .def_property_readonly("whole", &wholeOf, "a block's whole grid's cells (NX, NY, NZ); None for a whole grid")
        .def("cell_centres", &cellCentres,
             "(nx, ny, nz, 3) float32: every cell's centre, as the library computes it (see the class doc).")
        .def(py::pickle(
            [](const vds::Grid& g) {
                return py::make_tuple(tuple3(g.box.lo), tuple3(g.box.hi), dims3(g.dims), dims3(g.first), wholeOf(g));
            },
            [](const py::tuple& t) {
                // Three items: a grid pickled before blocks existed.
                if (t.size() != 3 && t.size() != 5) throw vds::InvalidArgument("not a pickled vds.Grid");
                return t.size() == 3 ? makeGrid(t[0], t[1], t[2], py::none(), py::none())
                                     : makeGrid(t[0], t[1], t[2], t[3], t[4]);
            }))
        .def("__repr__", [](const vds::Grid& g) {
            const auto t = [](const py::object& v) { return py::repr(v).cast<std::string>(); };
            std::string block;
            if (g.whole != glm::uvec3(0u)) block = ", first=" + t(dims3(g.first)) + ", whole=" + t(wholeOf(g));
            return "vds.Grid(lo=" + t(tuple3(g.box.lo)) + ", hi=" + t(tuple3(g.box.hi)) + ", dims=" + t(dims3(g.dims)) +
                   block + ")";
        });

}

/// The mesh files' and samples' functions: load_mesh, _sample_surface, _mesh_copies.
static void bindMeshFileFunctions(py::module_& m) {
    m.def("load_mesh", [](const py::object& path) {
              const std::string p = vds::python::fsPath(path);
              vds::python::requireNotDirectory(p);
              vds::TriangleMesh mesh;
              {
                  py::gil_scoped_release released;
                  mesh = vds::loadMesh(p);
              }
              return meshArraysOut(mesh);
          }, py::arg("path"), R"doc(
Reads an OBJ, PLY, STL or OFF mesh (path: str, bytes or os.PathLike):
returns (V, F), V a (n, 3) float64 array of positions in the file's units, F
a (m, 3) int32 array of vertex indices (polygons fanned into triangles).
Raises vds.IoError (an OSError) for a file that cannot be read (a directory
included), vds.FormatError (a ValueError) for a malformed one.)doc");
    m.def("_sample_surface", [](const py::object& vertices, const py::object& faces, std::uint64_t count,
                                std::uint64_t seed) {
              const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
              py::array_t<double> points({py::ssize_t(count), py::ssize_t(3)});
              py::array_t<std::uint32_t> triangles{py::ssize_t(count)};
              double* p = points.mutable_data();
              std::uint32_t* t = triangles.mutable_data();
              {
                  py::gil_scoped_release released;
                  vds::sampleSurface(mesh.view, count, seed, p, t);
              }
              return py::make_tuple(points, triangles);
          }, py::arg("V"), py::arg("F"), py::arg("n"), py::arg("seed"),
          "vds.sample_surface's compiled part: (points (n, 3) float64, triangles (n,) uint32).");
    m.def("_mesh_copies", [](const py::object& vertices, const py::object& faces) {
              const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
              return py::make_tuple(mesh.verticesCopied, mesh.facesCopied);
          }, "(V copied, F copied): whether (V, F) would be copied or read in place (for tests).");
}


void bindMeshFunctions(py::module_& m) {
    m.def("occupancy", &meshOccupancy, py::arg("V"), py::arg("F"), py::arg("grid"), py::arg("rule") = "parity",
          py::arg("threads") = 0, R"doc(
Exact labels of every cell centre of `grid` (a vds.Grid) for the mesh (V, F),
by one sweep per column along z on the triangles: a bool array of shape
grid.shape, [i, j, k] True inside, equal to the exact classifier's labels of
grid.cell_centres(). (Sprite.occupancy and Classifier.occupancy sweep the
other representations.))doc");
    m.def("validate_mesh", [](const py::object& vertices, const py::object& faces) {
              const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
              vds::MeshReport r;
              {
                  py::gil_scoped_release released;
                  r = vds::validateMesh(mesh.view);
              }
              py::dict d;
              d["vertices"] = r.vertexCount;
              d["triangles"] = r.triangleCount;
              d["boundary_edges"] = r.boundaryEdges;
              d["non_manifold_edges"] = r.nonManifoldEdges;
              d["odd_non_manifold_edges"] = r.oddNonManifoldEdges;
              d["inconsistent_edges"] = r.inconsistentEdges;
              d["inside_out_parts"] = r.insideOutParts;
              d["winding_boundary_edges"] = r.windingBoundaryEdges;
              d["status"] = r.status();
              d["degenerate_triangles"] = r.degenerateTriangles;
              d["duplicate_triangles"] = r.duplicateTriangles;
              d["isolated_vertices"] = r.isolatedVertices;
              d["non_finite_vertices"] = r.nonFiniteVertices;
              d["bad_indices"] = r.badIndices;
              d["closed"] = r.closed();
              d["oriented"] = r.oriented();
              d["manifold"] = r.manifold();
              d["usable"] = r.usable();
              d["bounds"] = py::make_tuple(tuple3(r.bounds.lo), tuple3(r.bounds.hi));
              d["summary"] = r.summary();
              return d;
          }, py::arg("V"), py::arg("F"), R"doc(
What the library's validation finds in the mesh (V, F), as `vds info` prints
it: a dict of counts ("boundary_edges", "non_manifold_edges",
"inconsistent_edges", "inside_out_parts", "winding_boundary_edges" (the
count of ExactClassifier.boundary_edges), "degenerate_triangles", ...),
"status" ("closed", "mis-oriented" or "open": Sprite.status's word), "closed"
(the parity rule defines inside), "oriented" (the winding rule too), "manifold", "usable",
"bounds" ((lo, hi) of the used vertices) and the one-line "summary". Indices
out of range raise vds.InvalidMesh, as everywhere.)doc");
    bindMeshFileFunctions(m);
}

} // namespace vds::python
