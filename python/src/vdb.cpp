// vds._vds: .vdb output (<vds/vdb.h>) for Python — write_vdb, a narrow band
// computed sparsely (vds::sparseBand) into an OpenVDB level set, or the
// exact occupancy into a BoolGrid; vdb_available says whether this build
// writes them (OpenVDB found when it was built).
#include "distance.h"

#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/sparse_band.h>
#include <vds/vdb.h>

#include "arrays.h"
#include "bindings.h"

namespace vds::python {

namespace {

/// The grid given, or cubic cells of `voxel_size` over the mesh's box grown
/// by the band and a cell (past the dense limit where it needs to be).
Grid vdbGrid(const py::object& gridObject, const py::object& voxelSize, const MeshView& mesh, double band) {
    if (gridObject.is_none() == voxelSize.is_none())
        throw InvalidArgument("give grid (a vds.Grid) or voxel_size (cubic cells over the mesh's box), one of them");
    if (!gridObject.is_none()) return gridFrom(gridObject);
    const double h = voxelSize.cast<double>();
    Box box = meshBounds(mesh);
    const float margin = float(band + h);
    box.lo -= glm::vec3(margin);
    box.hi += glm::vec3(margin);
    return voxelSizeGrid(box, h);
}

std::size_t writeVdbFile(const std::string& path, const py::object& vertices, const py::object& faces,
                         const py::object& gridObject, const py::object& voxelSize, const py::object& bandObject,
                         const py::object& ruleObject, bool occupancy, const py::object& threads,
                         const std::string& source) {
    if (!vdbAvailable()) writeVdb(path, SparseBand{}); // the one-line refusal
    std::optional<double> band;
    if (!bandObject.is_none()) band = bandObject.cast<double>();
    if (occupancy == band.has_value())
        throw InvalidArgument(occupancy ? "occupancy=True writes labels: leave band out"
                                        : "a level set needs band (its half-width, mesh units), or occupancy=True");
    const Rule rule = parseRule(textOption(ruleObject, "rule"));
    const unsigned threadsWanted = threadCount(threads);
    const MeshArrays mesh = meshArrays(vertices, faces);
    const Grid grid = vdbGrid(gridObject, voxelSize, mesh.view, band.value_or(0.0));
    VdbOptions options;
    options.source = source;
    warnIfOpen(mesh.view, rule); // as vds.signed_distance and vds.sdf warn
    py::gil_scoped_release released;
    const SignedDistance distance(mesh.view, rule);
    if (occupancy) {
        checkGrid(grid);
        std::vector<std::uint8_t> labels(grid.cellCount());
        ClassifyOptions classify;
        classify.rule = rule;
        classify.threads = threadsWanted;
        distance.classifier().occupancy(grid, labels.data(), classify);
        writeVdb(path, grid, labels.data(), rule, options);
        std::size_t inside = 0;
        for (std::uint8_t l : labels) inside += l;
        return inside;
    }
    const SparseBand sparse = sparseBand(distance, mesh.view, grid, SparseBandOptions{threadsWanted, *band});
    writeVdb(path, sparse, options);
    return sparse.values.size();
}

} // namespace

void registerVdb(py::module_& m) {
    m.def("vdb_available", &vdbAvailable,
          "True where this build writes .vdb files (OpenVDB, libopenvdb-dev, was found when vds was built).");
    m.def("write_vdb", &writeVdbFile, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("grid") = py::none(),
          py::kw_only(), py::arg("voxel_size") = py::none(), py::arg("band") = py::none(), py::arg("rule") = "parity",
          py::arg("occupancy") = false, py::arg("threads") = 0, py::arg("source") = "",
          R"doc(Writes an OpenVDB file of the mesh (V, F), whole or not at all; returns its active voxels.

With band=W (mesh units): the narrow band computed sparsely, only the cells
within W of the surface, as a FloatGrid "sdf" of class level set, background
W, each cell the value of vds.sdf(V, F, grid, rule, band=W) (the same floats
and signs), inside blocks as tiles. With occupancy=True: the exact labels of
vds.occupancy(V, F, grid, rule) as a BoolGrid "occupancy", whole 8^3 blocks
inside as active tiles. The cells: grid (a vds.Grid), or voxel_size=h, cubic
cells of side h over the mesh's box grown by the band and one cell (a band
may then pass the 2^34 cells of a vds.Grid: up to 2^40). Voxel (i, j, k) is
centred on cell (i, j, k). Metadata: rule, vds_version, source. pyopenvdb
(Debian's python3-openvdb) reads it: pyopenvdb.read(path, "sdf").
Raises vds.InvalidArgument where this build has no OpenVDB
(vds.vdb_available()), for a band that is not above 0, or grid and
voxel_size both or neither; vds.IoError when the file cannot be written.)doc");
}

} // namespace vds::python
