// vds._vds: exact distances (<vds/distance.h>) for Python — the class
// SignedDistance (built once from V, F and a rule, asked many times) and the
// one-call functions signed_distance, closest_points and sdf. Points enter
// through arrays.h like every classify call; the GIL is released while the
// hierarchy is built and while distances are computed.
#include "distance.h"

#include <limits>
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

/// vds.MeshWarning where `rule` does not define the mesh's inside (as
/// vds.exact_contains warns), at the caller's line and in Python's words;
/// the distances still come.
void warnIfOpen(const MeshView& mesh, Rule rule) {
    MeshReport report;
    {
        py::gil_scoped_release released;
        report = validateMesh(mesh);
    }
    // An unusable mesh: SignedDistance says why; a flat one has no sign to
    // warn about (its signed calls are refused, its unsigned ones answer).
    if (report.usable() && !report.flat()) warn(insideMessage(report, "", rule));
}

namespace {


/// A distance option (band): a real number, else `DTypeError` naming `what`
/// and the type given (pybind's own TypeError would print every argument).
double realOption(const py::object& value, const char* what) {
    const bool number = py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
                        py::isinstance(value, py::module_::import("numpy").attr("number"));
    if (!number || py::isinstance<py::bool_>(value))
        throw DTypeError(std::string(what) + " must be a number, not " + typeName(value));
    return value.cast<double>();
}

/// A yes/no option (propagated): a bool (Python's or numpy's), else `DTypeError`.
bool flagOption(const py::object& value, const char* what) {
    const py::object numpyBool = py::module_::import("numpy").attr("bool_");
    if (!py::isinstance<py::bool_>(value) && !py::isinstance(value, numpyBool))
        throw DTypeError(std::string(what) + " must be True or False, not " + typeName(value));
    return value.cast<bool>();
}

/// `max_distance`: None (no bound) or a positive number.
double maxDistanceOption(const py::object& value) {
    if (value.is_none()) return std::numeric_limits<double>::infinity();
    const double bound = realOption(value, "max_distance");
    if (!(bound > 0.0))
        throw InvalidArgument("max_distance must be positive (None: no bound), not " + std::to_string(bound));
    return bound;
}

class PySignedDistance {
public:
    PySignedDistance(const py::object& vertices, const py::object& faces, const py::object& rule) {
        const Rule r = parseRule(textOption(rule, "rule"));
        const MeshArrays mesh = meshArrays(vertices, faces);
        warnIfOpen(mesh.view, r);
        py::gil_scoped_release released;
        distance_ = std::make_unique<SignedDistance>(mesh.view, r); // copies the triangles
        mesh_ = std::make_shared<const MeshCopy>(mesh.view);
    }

    /// Pickled as what rebuilds it: (V float32, F uint32, rule).
    py::tuple state() const {
        const py::tuple arrays = mesh_->arrays();
        return py::make_tuple(arrays[0], arrays[1], rule());
    }

    py::array_t<double> distance(const py::object& points, const py::object& threads, const py::object& maxDistance,
                                 bool isSigned) const {
        DistanceOptions options;
        options.threads = threadCount(threads);
        options.maxDistance = maxDistanceOption(maxDistance);
        Points p = viewPoints(points);
        py::array_t<double> out(py::ssize_t(p.count));
        double* d = out.mutable_data();
        py::gil_scoped_release released;
        p.prepare(false);
        if (isSigned) distance_->distance(p.points, d, options);
        else distance_->unsignedDistance(p.points, d, options);
        return out;
    }

    py::tuple closest(const py::object& points, const py::object& threads, const py::object& maxDistance,
                      const py::object& featuresObject) const {
        DistanceOptions options;
        options.threads = threadCount(threads);
        options.maxDistance = maxDistanceOption(maxDistance);
        const bool features = flagOption(featuresObject, "features");
        Points p = viewPoints(points);
        std::vector<ClosestPoint> closest(p.count);
        {
            py::gil_scoped_release released;
            p.prepare(false);
            distance_->closestPoints(p.points, closest.data(), options);
        }
        const auto n = py::ssize_t(p.count);
        py::array_t<double> xyz({n, py::ssize_t(3)});
        py::array_t<double> d(n);
        py::array_t<std::uint32_t> triangles(n);
        py::array_t<std::uint8_t> feature(n), index(n);
        double* x = xyz.mutable_data();
        for (std::size_t k = 0; k < closest.size(); ++k) {
            for (int a = 0; a < 3; ++a) x[3 * k + a] = closest[k].point[a];
            d.mutable_data()[k] = closest[k].distance;
            triangles.mutable_data()[k] = closest[k].triangle;
            feature.mutable_data()[k] = std::uint8_t(closest[k].feature);
            index.mutable_data()[k] = closest[k].index;
        }
        if (features) return py::make_tuple(xyz, d, triangles, feature, index);
        return py::make_tuple(xyz, d, triangles);
    }

    py::array_t<float> grid(const py::object& gridObject, const py::object& bandObject,
                            const py::object& propagatedObject, const py::object& threads) const {
        const Grid grid = gridFrom(gridObject);
        const double band = realOption(bandObject, "band");
        const bool propagated = flagOption(propagatedObject, "propagated");
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
    std::shared_ptr<const MeshCopy> mesh_; ///< what rebuilds it (pickling)
};

/// vds.SignedDistance: built once, asked many times.
void registerSignedDistance(py::module_& m) {
    py::class_<PySignedDistance>(m, "SignedDistance", R"doc(
Exact distances to the mesh (V, F), signed by a rule: built once (a bounding
volume hierarchy over the triangles and the exact classifier), asked many
times. SignedDistance(V, F, rule="parity"); rule "parity" or "winding" for a
closed mesh, "generalized-winding" for open, messy or badly oriented ones.
A distance is negative exactly where vds.exact_contains(V, F, points, rule)
is True. Points are (N, 3) float32 or float64, rounded to float32 first (as
every classifier does); distances are float64, mesh units, exact up to
double rounding. Raises vds.InvalidMesh for an empty or unusable mesh; a flat
one (a sheet) has unsigned_distance and closest_points, while distance and sdf
raise vds.InvalidMesh (no inside, no sign); vds.InvalidArgument for a point that is not finite; warns (vds.MeshWarning)
where the rule does not define the mesh's inside (an open mesh by parity or
winding: crossings are counted as for a surface), at the caller's line.
Raises vds.DTypeError (a TypeError) for an argument of the wrong type (a rule
that is not a str, a grid that is not a vds.Grid, a band that is not a
number). Pickles as (V, F, rule), rebuilt where it is unpickled, so it goes
to Dask workers and multiprocessing pools.)doc")
        .def(py::init<const py::object&, const py::object&, const py::object&>(), py::arg("V"), py::arg("F"),
             py::arg("rule") = "parity")
        .def("distance", [](const PySignedDistance& s, const py::object& p, const py::object& t,
                            const py::object& bound) { return s.distance(p, t, bound, true); },
             py::arg("points"), py::arg("threads") = 0, py::arg("max_distance") = py::none(),
             "(N,) float64 signed distances, negative inside. max_distance: search no farther; a point farther "
             "from every triangle gets +-max_distance (signed by its label), cheaper far from the surface.")
        .def("unsigned_distance", [](const PySignedDistance& s, const py::object& p, const py::object& t,
                                     const py::object& bound) { return s.distance(p, t, bound, false); },
             py::arg("points"), py::arg("threads") = 0, py::arg("max_distance") = py::none(),
             "(N,) float64 distances to the surface; max_distance as for distance().")
        .def("closest_points", &PySignedDistance::closest, py::arg("points"), py::arg("threads") = 0,
             py::arg("max_distance") = py::none(), py::arg("features") = false,
             "(points (N, 3) float64, distances (N,) float64, triangles (N,) uint32): each point's nearest "
             "point of the surface, its unsigned distance, and the index into F of the triangle it lies on. "
             "max_distance: search no farther; a point farther from every triangle gets distance max_distance "
             "and triangle vds.NO_TRIANGLE (its point is meaningless). features=True adds (features (N,) uint8, "
             "indices (N,) uint8): where on its triangle the point lies, vds.FEATURES[f] ('face', 'edge', "
             "'vertex'), and which edge (from corner i to corner (i + 1) % 3) or corner.")
        .def("sdf", &PySignedDistance::grid, py::arg("grid"), py::arg("band") = 0.0, py::arg("propagated") = false,
             py::arg("threads") = 0,
             "float32 array of grid.shape: the signed distance of every cell centre (grid.cell_centres()); "
             "band > 0: cells farther than band from the surface hold -band or +band; propagated: the full grid "
             "as a closest-feature transform, exact within a cell diagonal of the surface, beyond it never "
             "below the distance and within 4 cell diagonals above it.")
        .def_property_readonly("rule", &PySignedDistance::rule)
        .def(py::pickle([](const PySignedDistance& s) { return s.state(); },
                        [](const py::tuple& t) {
                            if (t.size() != 3) throw InvalidArgument("not a pickled vds.SignedDistance");
                            return std::make_unique<PySignedDistance>(t[0], t[1], t[2]);
                        }))
        .def("__repr__", [](const PySignedDistance& s) { return "<vds.SignedDistance: " + s.summary() + ">"; });
}

} // namespace

void registerDistance(py::module_& m) {
    registerSignedDistance(m);
    m.def("signed_distance", [](const py::object& v, const py::object& f, const py::object& points,
                                const py::object& rule, const py::object& threads, const py::object& maxDistance) {
              return PySignedDistance(v, f, rule).distance(points, threads, maxDistance, true);
          }, py::arg("V"), py::arg("F"), py::arg("points"), py::arg("rule") = "parity", py::arg("threads") = 0,
          py::arg("max_distance") = py::none(),
          "Signed distances of points (N, 3) to the mesh (V, F): (N,) float64, negative exactly where the "
          "exact classifier of `rule` says inside. Builds a SignedDistance for the call: keep one to ask many times.");
    m.def("closest_points", [](const py::object& v, const py::object& f, const py::object& points,
                               const py::object& threads, const py::object& maxDistance, const py::object& features) {
              const PySignedDistance any(v, f, py::str("generalized-winding"));
              return any.closest(points, threads, maxDistance, features);
          }, py::arg("V"), py::arg("F"), py::arg("points"), py::arg("threads") = 0,
          py::arg("max_distance") = py::none(), py::arg("features") = false,
          "(points (N, 3) float64, distances (N,) float64, triangles (N,) uint32): the nearest point of the "
          "surface (V, F) to each point, its distance and its triangle. Any usable mesh, a flat one (a sheet) too. "
          "max_distance and features as for SignedDistance.closest_points.");
    m.attr("NO_TRIANGLE") = py::int_(kNoTriangle);
    py::tuple features(3);
    for (const auto& entry : EnumNames<Feature>::table) features[std::size_t(entry.value)] = py::str(entry.name);
    m.attr("FEATURES") = features;
    m.def("sdf", [](const py::object& v, const py::object& f, const py::object& grid, const py::object& rule,
                    const py::object& band, const py::object& propagated, const py::object& threads) {
              return PySignedDistance(v, f, rule).grid(grid, band, propagated, threads);
          }, py::arg("V"), py::arg("F"), py::arg("grid"), py::arg("rule") = "parity", py::arg("band") = 0.0,
          py::arg("propagated") = false, py::arg("threads") = 0,
          "A signed distance grid: float32 of grid.shape, [i, j, k] the signed distance of that cell's centre, "
          "negative where vds.occupancy(V, F, grid, rule) is True; band > 0 clamps cells farther than band to "
          "-band / +band; propagated=True fills the full grid as a closest-feature transform (exact near the "
          "surface, within 4 cell diagonals beyond).");
}

} // namespace vds::python
