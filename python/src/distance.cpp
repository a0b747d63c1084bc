// vds._vds: exact distances (<vds/distance.h>) for Python — the class
// SignedDistance (built once from V, F and a rule, asked many times) and the
// one-call functions signed_distance, closest_points and sdf. Points enter
// through arrays.h like every classify call; the GIL is released while the
// hierarchy is built and while distances are computed.
#include "distance.h"

#include <memory>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vds/distance.h>
#include <vds/error.h>
#include <vds/mesh_check.h>

#include "arrays.h"
#include "bindings.h"

namespace vds::python {

namespace {

/// vds.MeshWarning with the CLI's text where `rule` does not define the
/// mesh's inside (as vds.exact_contains warns); the distances still come.
void warnIfOpen(const MeshView& mesh, Rule rule) {
    MeshReport report;
    {
        py::gil_scoped_release released;
        report = validateMesh(mesh);
    }
    if (!report.usable()) return; // SignedDistance says why
    std::string message = openMeshMessage(report, "", rule, pythonFlags());
    if (message.empty()) message = insideWarning(report, rule, pythonFlags());
    if (message.empty()) return;
    const py::object category = py::module_::import("vds._vds").attr("MeshWarning");
    if (PyErr_WarnEx(category.ptr(), message.c_str(), 2) < 0) throw py::error_already_set();
}

class PySignedDistance {
public:
    PySignedDistance(const py::object& vertices, const py::object& faces, const std::string& rule) {
        const Rule r = parseRule(rule);
        const MeshArrays mesh = meshArrays(vertices, faces);
        warnIfOpen(mesh.view, r);
        py::gil_scoped_release released;
        distance_ = std::make_unique<SignedDistance>(mesh.view, r); // copies the triangles
    }

    py::array_t<double> distance(const py::object& points, const py::object& threads, bool isSigned) const {
        DistanceOptions options;
        options.threads = threadCount(threads);
        Points p = viewPoints(points);
        py::array_t<double> out(py::ssize_t(p.count));
        double* d = out.mutable_data();
        py::gil_scoped_release released;
        p.prepare(false);
        if (isSigned) distance_->distance(p.points, d, options);
        else distance_->unsignedDistance(p.points, d, options);
        return out;
    }

    py::tuple closest(const py::object& points, const py::object& threads) const {
        DistanceOptions options;
        options.threads = threadCount(threads);
        Points p = viewPoints(points);
        std::vector<ClosestPoint> closest(p.count);
        {
            py::gil_scoped_release released;
            p.prepare(false);
            distance_->closestPoints(p.points, closest.data(), options);
        }
        py::array_t<double> xyz({py::ssize_t(p.count), py::ssize_t(3)});
        py::array_t<double> d(py::ssize_t(p.count));
        py::array_t<std::uint32_t> triangles(py::ssize_t(p.count));
        double* x = xyz.mutable_data();
        for (std::size_t k = 0; k < closest.size(); ++k) {
            for (int a = 0; a < 3; ++a) x[3 * k + a] = closest[k].point[a];
            d.mutable_data()[k] = closest[k].distance;
            triangles.mutable_data()[k] = closest[k].triangle;
        }
        return py::make_tuple(xyz, d, triangles);
    }

    py::array_t<float> grid(const Grid& grid, double band, bool propagated, const py::object& threads) const {
        if (propagated && band != 0.0)
            throw InvalidArgument("propagated is a way to fill the full grid: leave band at 0");
        DistanceGridOptions options;
        options.band = band;
        options.far = propagated ? FarCells::Propagated : FarCells::Exact;
        options.threads = threadCount(threads);
        checkGrid(grid);
        py::array_t<float> cells({py::ssize_t(grid.dims.x), py::ssize_t(grid.dims.y), py::ssize_t(grid.dims.z)});
        float* out = cells.mutable_data();
        py::gil_scoped_release released;
        distance_->grid(grid, out, options);
        return cells;
    }

    std::string summary() const { return distance_->summary(); }
    std::string rule() const { return toString(distance_->rule()); }

private:
    std::unique_ptr<SignedDistance> distance_;
};

} // namespace

void registerDistance(py::module_& m) {
    py::class_<PySignedDistance>(m, "SignedDistance", R"doc(
Exact distances to the mesh (V, F), signed by a rule: built once (a bounding
volume hierarchy over the triangles and the exact classifier), asked many
times. SignedDistance(V, F, rule="parity"); rule "parity" or "winding" for a
closed mesh, "generalized-winding" for open, messy or badly oriented ones.
A distance is negative exactly where vds.exact_contains(V, F, points, rule)
is True. Points are (N, 3) float32 or float64, rounded to float32 first (as
every classifier does); distances are float64, mesh units, exact up to
double rounding. Raises vds.InvalidMesh for an empty, flat or unusable mesh,
vds.InvalidArgument for a point that is not finite; warns (vds.MeshWarning)
where the rule does not define the mesh's inside (an open mesh by parity or
winding: crossings are counted as for a surface).)doc")
        .def(py::init<const py::object&, const py::object&, const std::string&>(), py::arg("V"), py::arg("F"),
             py::arg("rule") = "parity")
        .def("distance", [](const PySignedDistance& s, const py::object& p, const py::object& t) {
                 return s.distance(p, t, true);
             }, py::arg("points"), py::arg("threads") = 0, "(N,) float64 signed distances, negative inside.")
        .def("unsigned_distance", [](const PySignedDistance& s, const py::object& p, const py::object& t) {
                 return s.distance(p, t, false);
             }, py::arg("points"), py::arg("threads") = 0, "(N,) float64 distances to the surface.")
        .def("closest_points", &PySignedDistance::closest, py::arg("points"), py::arg("threads") = 0,
             "(points (N, 3) float64, distances (N,) float64, triangles (N,) uint32): each point's nearest "
             "point of the surface, its unsigned distance, and the index into F of the triangle it lies on.")
        .def("sdf", &PySignedDistance::grid, py::arg("grid"), py::arg("band") = 0.0, py::arg("propagated") = false,
             py::arg("threads") = 0,
             "float32 array of grid.shape: the signed distance of every cell centre (grid.cell_centres()); "
             "band > 0: cells farther than band from the surface hold -band or +band; propagated: the full grid "
             "as a closest-feature transform, exact within a cell diagonal of the surface, beyond it never "
             "below the distance and within 4 cell diagonals above it.")
        .def_property_readonly("rule", &PySignedDistance::rule)
        .def("__repr__", [](const PySignedDistance& s) { return "<vds.SignedDistance: " + s.summary() + ">"; });

    m.def("signed_distance", [](const py::object& v, const py::object& f, const py::object& points,
                                const std::string& rule, const py::object& threads) {
              return PySignedDistance(v, f, rule).distance(points, threads, true);
          }, py::arg("V"), py::arg("F"), py::arg("points"), py::arg("rule") = "parity", py::arg("threads") = 0,
          "Signed distances of points (N, 3) to the mesh (V, F): (N,) float64, negative exactly where the "
          "exact classifier of `rule` says inside. Builds a SignedDistance for the call: keep one to ask many times.");
    m.def("closest_points", [](const py::object& v, const py::object& f, const py::object& points,
                               const py::object& threads) {
              return PySignedDistance(v, f, "generalized-winding").closest(points, threads);
          }, py::arg("V"), py::arg("F"), py::arg("points"), py::arg("threads") = 0,
          "(points (N, 3) float64, distances (N,) float64, triangles (N,) uint32): the nearest point of the "
          "surface (V, F) to each point, its distance and its triangle. Any usable mesh that is not flat.");
    m.def("sdf", [](const py::object& v, const py::object& f, const Grid& grid, const std::string& rule,
                    double band, bool propagated, const py::object& threads) {
              return PySignedDistance(v, f, rule).grid(grid, band, propagated, threads);
          }, py::arg("V"), py::arg("F"), py::arg("grid"), py::arg("rule") = "parity", py::arg("band") = 0.0,
          py::arg("propagated") = false, py::arg("threads") = 0,
          "A signed distance grid: float32 of grid.shape, [i, j, k] the signed distance of that cell's centre, "
          "negative where vds.occupancy(V, F, grid, rule) is True; band > 0 clamps cells farther than band to "
          "-band / +band; propagated=True fills the full grid as a closest-feature transform (exact near the "
          "surface, within 4 cell diagonals beyond).");
}

} // namespace vds::python
