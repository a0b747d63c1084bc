// vds.Sprite and the functions that make one (bake, read, from_bytes).
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
#include <vds/vds_file.h>

#include <glm/mat4x4.hpp>

#include "arrays.h"
#include "bindings.h"

namespace py = pybind11;
using vds::python::DTypeError;
using vds::python::MeshArrays;
using vds::python::Points;

namespace vds::python {

std::shared_ptr<PySprite> wrap(vds::Sprite&& sprite) { return std::make_shared<PySprite>(std::move(sprite)); }

std::shared_ptr<PySprite> spriteFromBytes(const py::bytes& data, const std::string& name) {
    const std::string_view view(data);
    py::gil_scoped_release released;
    return wrap(vds::decodeSprite(view.data(), view.size(), name));
}

namespace {


/// The sprite's resident copy, uploaded on its first GPU call (or the first
/// after _release_gl), placed as the sprite is now (transform() changes only
/// the placement). On the GL thread.
const vds::GpuSprite& residentCopy(GlState& s, PySprite& sprite) {
    s.context();
    auto it = sprite.gpuId ? s.resident.find(sprite.gpuId) : s.resident.end();
    if (it == s.resident.end()) {
        auto copy = std::make_unique<vds::GpuSprite>(sprite);
        if (!sprite.gpuId) sprite.gpuId = nextGlId.fetch_add(1);
        it = s.resident.emplace(sprite.gpuId, std::move(copy)).first;
    }
    it->second->setPlacement(sprite.grid);
    return *it->second;
}

BoolArray spriteContains(PySprite& sprite, const py::object& points, const py::object& rule, bool gpu,
                         const py::object& threads) {
    const vds::ClassifyOptions options = classifyOptions(rule, threads);
    warnOpenSprite(sprite, options.rule);
    Points p = vds::python::viewPoints(points);
    BoolArray labels(py::ssize_t(p.count));
    auto* out = reinterpret_cast<std::uint8_t*>(labels.mutable_data());
    py::gil_scoped_release released;
    p.prepare(gpu);
    if (p.count == 0) return labels;
    if (!gpu) {
        vds::classify(sprite, p.points, out, options);
        return labels;
    }
    glThread().run([&](GlState& s) {
        const vds::GpuSprite& copy = residentCopy(s, sprite);
        if (!s.classifier) s.classifier = std::make_unique<vds::GpuClassifier>(*s.gl);
        s.classifier->classify(copy, vds::PointsView(p.vec3(), p.count), out, options);
    });
    return labels;
}

BoolArray spriteOccupancy(PySprite& sprite, const py::object& gridObject, const py::object& rule, bool gpu,
                          const py::object& threads) {
    const vds::Grid grid = gridFrom(gridObject);
    const vds::ClassifyOptions options = classifyOptions(rule, threads);
    warnOpenSprite(sprite, options.rule);
    BoolArray cells = vds::python::gridArray(grid);
    auto* out = reinterpret_cast<std::uint8_t*>(cells.mutable_data());
    py::gil_scoped_release released;
    if (!gpu) {
        vds::occupancy(sprite, grid, out, options);
        return cells;
    }
    vds::checkGrid(grid);
    if (vds::sweepsByColumns(sprite.grid)) { // the condition of GpuOccupancy's column sweep
        glThread().run([&](GlState& s) {
            const vds::GpuSprite& copy = residentCopy(s, sprite);
            if (!s.occupancy) s.occupancy = std::make_unique<vds::GpuOccupancy>(*s.gl);
            s.occupancy->occupancy(copy, grid, out, options);
        });
        return cells;
    }
    // Rotated since the bake: the cell centres, one by one.
    std::vector<glm::vec3> centres(grid.cellCount());
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) centres[grid.index(i, j, k)] = grid.cellCentre(i, j, k);
    glThread().run([&](GlState& s) {
        const vds::GpuSprite& copy = residentCopy(s, sprite);
        if (!s.classifier) s.classifier = std::make_unique<vds::GpuClassifier>(*s.gl);
        s.classifier->classify(copy, vds::PointsView(centres), out, options);
    });
    return cells;
}

py::array_t<double> spriteWinding(const PySprite& sprite, const py::object& points) {
    if (!sprite.boundaryKnown)
        throw vds::InvalidArgument("the sprite's boundary is unknown (a version 1 .vds file): no winding numbers");
    Points p = vds::python::viewPoints(points);
    py::array_t<double> numbers(py::ssize_t(p.count));
    double* out = numbers.mutable_data();
    py::gil_scoped_release released;
    p.prepare(false);
    for (std::size_t k = 0; k < p.count; ++k) out[k] = shownWinding(sprite.generalizedWinding(p.points[k]));
    return numbers;
}

/// vds.bake: the mesh's warning (as `vds bake` prints it), then the bake.
/// Refuses a distance grid of `cells` along the longest side of `box` that
/// one attribute of a .vds file cannot hold (as `vds bake --distance`).
void requireDistanceFits(const vds::Box& box, std::uint32_t cells) {
    const vds::Grid grid = vds::spriteDistanceGrid(box, cells);
    if (grid.cellCount() > vds::kMaxDistanceCells)
        throw vds::InvalidArgument("a distance grid of " + std::to_string(grid.dims.x) + " x " +
                                   std::to_string(grid.dims.y) + " x " + std::to_string(grid.dims.z) +
                                   " cells is more than a sprite file holds (" +
                                   std::to_string(vds::kMaxDistanceCells) + "); lower distance");
}

/// The sprite's signed distance grid of `cells` along its box's longest
/// side, by `rule`, as `vds bake --distance` stores it. Without the GIL.
void addDistance(vds::Sprite& sprite, MeshView mesh, std::uint32_t cells, vds::Rule rule) {
    sprite.distance.grid = vds::spriteDistanceGrid(sprite.grid.box, cells);
    const vds::SignedDistance query(mesh, rule, sprite.sourceName);
    sprite.distance.cells.resize(sprite.distance.grid.cellCount());
    query.grid(sprite.distance.grid, sprite.distance.cells.data(), {});
}

std::shared_ptr<PySprite> bakeMesh(const py::object& vertices, const py::object& faces, const py::object& resolution,
                                   const py::object& axisObject, const py::object& methodObject,
                                   const std::string& name, const py::object& distanceObject,
                                   const py::object& distanceRuleObject) {
    const std::uint32_t distance = vds::python::countOption(distanceObject, "distance");
    const vds::Rule distanceRule = vds::parseRule(textOption(distanceRuleObject, "distance_rule"));
    const std::string axis = textOption(axisObject, "axis"), method = textOption(methodObject, "method");
    const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
    vds::BakeOptions options;
    options.resolution = vds::python::countOption(resolution, "resolution");
    options.method = vds::parseBakeMethod(method);
    options.sourceName = name;
    const bool autoAxis = axis == "auto";
    if (!autoAxis) options.axis = vds::parseAxis(axis);
    vds::MeshReport report;
    {
        py::gil_scoped_release released;
        report = vds::validateMesh(mesh.view);
    }
    vds::requireUsable(report, name);
    if (distance != 0) requireDistanceFits(report.bounds, distance); // before the bake
    warn(insideMessage(report, name, vds::Rule::Parity));
    py::gil_scoped_release released;
    if (autoAxis) options.axis = vds::chooseViewAxis(mesh.view, options.resolution).axis;
    // Auto: the CPU baker where no GL can be had; on a context, the GL layer's choice.
    if (options.method == vds::BakeMethod::Auto && !vds::glAvailable()) options.method = vds::BakeMethod::Cpu;
    vds::Sprite sprite;
    if (options.method == vds::BakeMethod::Cpu)
        sprite = vds::bakeCpu(mesh.view, options);
    else
        glThread().run([&](GlState& s) { sprite = vds::bake(s.context(), mesh.view, options); });
    if (distance != 0) addDistance(sprite, mesh.view, distance, distanceRule);
    return wrap(std::move(sprite));
}

/// Sprite.distance: None, or (values, grid).
py::object spriteDistance(const PySprite& sprite) {
    if (sprite.distance.empty()) return py::none();
    const vds::Grid& g = sprite.distance.grid;
    py::array_t<float> values({py::ssize_t(g.dims.x), py::ssize_t(g.dims.y), py::ssize_t(g.dims.z)});
    std::memcpy(values.mutable_data(), sprite.distance.cells.data(), sprite.distance.cells.size() * sizeof(float));
    return py::make_tuple(values, py::cast(g));
}


py::bytes spriteBytes(const PySprite& sprite) {
    std::vector<char> data;
    {
        py::gil_scoped_release released;
        data = vds::encodeSprite(sprite);
    }
    return py::bytes(data.data(), data.size());
}

glm::mat4 matrixFrom(const py::object& object) {
    auto m = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
    if (!m || m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4)
        throw vds::InvalidArgument("matrix must have shape (4, 4)");
    glm::mat4 model(1.0f);
    const auto a = m.unchecked<2>();
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) {
            if (!std::isfinite(a(row, column))) throw vds::InvalidArgument("matrix has a non-finite entry");
            model[column][row] = float(a(row, column)); // glm is column-major
        }
    return model;
}

} // namespace

namespace {

using SpriteClass = py::class_<PySprite, std::shared_ptr<PySprite>>;

/// Its queries and writers: contains, occupancy, winding_numbers, transform, save, to_bytes.
void defineSpriteQueries(SpriteClass& sprite) {
    sprite
        .def("contains", &spriteContains, py::arg("points"), py::arg("rule") = "parity", py::arg("gpu") = false,
             py::arg("threads") = 0, (std::string(R"doc(
Inside tests of points.

points: (N, 3) float32 or float64 array (any strides; x, y, z adjacent is
    read in place), world coordinates: the mesh's units, moved by
    `transform`. Points outside the sprite's box are outside.)doc") + kRuleDoc + R"doc(
gpu: classify with the GL compute shader on the module's headless context
    (answers identical to the CPU's; for "generalized-winding" on an open
    mesh the boundary term is summed in float, which can flip a label where
    the winding number is within float error, up to about 1e-4 near the
    holes' rims, of 1/2). The sprite is
    uploaded on its first gpu=True call and stays resident on the GPU until
    it is freed (or vds._release_gl runs at exit); `transform` only moves
    it. Calls from several threads take turns.
threads: CPU threads, 0: one per hardware thread.
Returns a (N,) bool array, True inside. Raises vds.DTypeError (a TypeError)
for points that are not float32/float64, vds.InvalidArgument (a ValueError)
for another shape or a non-finite coordinate. Releases the GIL while it works.)doc").c_str())
        .def("occupancy", &spriteOccupancy, py::arg("grid"), py::arg("rule") = "parity", py::arg("gpu") = false,
             py::arg("threads") = 0, R"doc(
Labels every cell centre of `grid` (a vds.Grid): a bool array of shape
grid.shape, [i, j, k] True inside; the same labels as `contains` of
grid.cell_centres(). Each grid column along the view axis is one walk over
its crossings (on the CPU, or with gpu=True in a compute shader on the
module's context: the same labels) while the sprite is not rotated; the
cells one by one otherwise. rule and threads as for `contains`.)doc")
        .def("winding_numbers", &spriteWinding, py::arg("points"), R"doc(
(N, 3) float points -> (N,) float64 generalized winding numbers from the
sprite: the signed crossing count of the point's column in front of it plus
the Antipodal boundary term, both at the point moved onto its texel's centre
ray (so it errs only by the winding number's change over 0.71 texel across
the view axis). 1 inside and 0 outside a closed mesh, fractional near the
holes of an open one. Outside the sprite's box no crossing lies in front, so
the value is the boundary term alone: 0 for a closed mesh, the open mesh's
own (non-zero) value near its holes. `ExactClassifier` gives the exact values. Raises vds.InvalidArgument for a version 1 file of an open mesh.)doc")
        .def("transform", [](PySprite& s, const py::object& matrix) { s.transform(matrixFrom(matrix)); },
             py::arg("matrix"), R"doc(
Moves the sprite by a (4, 4) affine, invertible matrix (row-major, acting on
column vectors [x, y, z, 1]), on top of its current placement, without
re-baking: a sprite of solid S answers for matrix(S) afterwards.)doc")
        .def("save", [](const PySprite& s, const py::object& path) {
                 const std::string p = vds::python::fsPath(path);
                 vds::python::requireNotDirectory(p);
                 py::gil_scoped_release released;
                 vds::writeSprite(s, p);
             }, py::arg("path"), "Writes the sprite as a .vds file (path: str, bytes or os.PathLike), atomically "
                                 "(temporary file, then rename).")
        .def("to_bytes", &spriteBytes, "The bytes of the sprite's .vds file (what `save` writes).");
}

/// Its properties, repr and pickling.
void defineSpriteProperties(SpriteClass& sprite) {
    sprite
        .def_property_readonly("resolution", [](const PySprite& s) { return std::max(s.width(), s.height()); },
                               "texels on the longer side of the view (the bake's resolution)")
        .def_property_readonly("width", &vds::Sprite::width, "texel columns along s")
        .def_property_readonly("height", &vds::Sprite::height, "texel rows along t")
        .def_property_readonly("depth_complexity", [](const PySprite& s) { return s.depthComplexity; },
                               "d_S: the most surface crossings in any texel column (layers)")
        .def_property_readonly("box", [](const PySprite& s) {
                 py::array_t<double> box({py::ssize_t(2), py::ssize_t(3)});
                 auto b = box.mutable_unchecked<2>();
                 for (int c = 0; c < 3; ++c) {
                     b(0, c) = s.grid.box.lo[c];
                     b(1, c) = s.grid.box.hi[c];
                 }
                 return box;
             }, "(2, 3) float64: the baked mesh's bounding box [lo, hi], mesh coordinates (before transform)")
        .def_property_readonly("status", [](const PySprite& s) { return vds::statusWord(s.status, s.validation); },
                               "\"closed\" (every rule answers alike for the mesh's solid), \"mis-oriented\" "
                               "(closed, but orientation conflicts or an inside-out part: the rules disagree) or "
                               "\"open\" (holes: parity and winding answer a surface's crossings); the word of "
                               "validate_mesh(V, F)[\"status\"] and of `vds info`")
        .def_property_readonly("validation", [](const PySprite& s) { return s.validation; },
                               "the mesh validation summary recorded at bake time")
        .def_property_readonly("axis", [](const PySprite& s) { return vds::toString(s.grid.axis); },
                               "the view axis, \"x\", \"y\" or \"z\"")
        .def_property_readonly("source_name", [](const PySprite& s) { return s.sourceName; },
                               "the mesh's name given to the bake (`name`; the file's name for `vds bake`), \"\" if none")
        .def_property_readonly("memory_bytes", &vds::Sprite::memoryBytes, "bytes of host memory the layers take")
        .def_property_readonly("distance", &spriteDistance,
                               "the signed distance grid baked with the sprite (bake(distance=N), vds bake "
                               "--distance N): (values, grid), values float32 of grid.shape, [i, j, k] the signed "
                               "distance of grid cell (i, j, k)'s centre (grid.lo, grid.spacing; negative inside); "
                               "None without one")
        .def("__repr__", [](const PySprite& s) {
            return "<vds.Sprite " + std::to_string(s.width()) + "x" + std::to_string(s.height()) + ", " +
                   std::to_string(s.depthComplexity) + " layers, axis " + vds::toString(s.grid.axis) + ", " +
                   vds::statusWord(s.status, s.validation) +
                   (s.sourceName.empty() ? "" : ", from " + s.sourceName) + ">";
        })
        .def(py::pickle([](const PySprite& s) { return spriteBytes(s); },
                        [](const py::bytes& b) { return spriteFromBytes(b, "<pickle>"); }));
}

/// The functions that make a Sprite: bake, read, from_bytes.
void bindSpriteMakers(py::module_& m) {
    m.def("bake", &bakeMesh, py::arg("V"), py::arg("F"), py::arg("resolution") = 1024, py::arg("axis") = "auto",
          py::arg("method") = "auto", py::arg("name") = "", py::arg("distance") = 0,
          py::arg("distance_rule") = "parity", R"doc(
Bakes a triangle mesh into a Sprite.

V: (n, 3) float32/float64 vertex positions (mesh units; kept as float32).
F: (m, 3) integer vertex indices, counter-clockwise seen from outside.
    float32 V and int32/uint32 F, C-contiguous, are read in place.
resolution: texels on the longer side of the view, 1..16384.
axis: "x", "y", "z", or "auto" (the default: the axis with the fewest
    layers at this resolution, counted exactly).
method: "auto" (the default: GL fragment lists on a GPU, the CPU baker on a
    software renderer or without GL), "lists" (GL fragment lists), "peel"
    (GL depth peeling) or "cpu" (exact ray casting, no GL).
name: the mesh's name, in messages and recorded in the sprite.
distance: also store a signed distance grid of this many cubic cells along
    the box's longest side (4..1024, and at most 2^29 cells in all: 812 for
    a cube; 0, the default: none), checked before the bake; exact distances
    signed by distance_rule ("parity", "winding" or "generalized-winding"),
    as `vds bake --distance N`: Sprite.distance, written with the sprite
    (format version 3), and vdsDistance in GLSL.
Raises vds.InvalidMesh for an unusable mesh (empty, non-finite, bad
indices); an open mesh is baked with status "open", a closed but
mis-oriented one with status "mis-oriented", each with a vds.MeshWarning. GL methods raise vds.GlUnavailable where no GL
context can be had. Releases the GIL.)doc");
    m.def("read", [](const py::object& path) {
              const std::string p = vds::python::fsPath(path);
              vds::python::requireNotDirectory(p);
              py::gil_scoped_release released;
              return wrap(vds::readSprite(p));
          }, py::arg("path"),
          "Reads a .vds file (path: str, bytes or os.PathLike). Raises vds.IoError (an OSError) if it cannot be "
          "read (a directory included), vds.FormatError (a ValueError) if it is not a valid .vds file.");
    m.def("from_bytes", &spriteFromBytes, py::arg("data"), py::arg("name") = "<memory>",
          "The Sprite whose .vds file bytes are `data` (see Sprite.to_bytes). Raises vds.FormatError for bad bytes.");
}

} // namespace

void bindSprite(py::module_& m) {
    SpriteClass sprite(m, "Sprite", R"doc(
A volumetric depth sprite: a closed mesh baked into layered depth columns.

Made by `vds.bake`, `vds.read` or `vds.from_bytes`. Answers inside/outside
for points in the mesh's coordinates (after any `transform`). Classifying is
thread safe; `transform` must not run while another thread classifies.
Pickles as its .vds file bytes.)doc");
    defineSpriteQueries(sprite);
    defineSpriteProperties(sprite);
    bindSpriteMakers(m);
}

} // namespace vds::python
