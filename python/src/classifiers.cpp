// vds.Classifier (every method of the library's contract) and vds.ExactClassifier.
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

#include "arrays.h"
#include "bindings.h"

namespace py = pybind11;
using vds::python::DTypeError;
using vds::python::MeshArrays;
using vds::python::Points;

namespace vds::python {

namespace {

class PyExact {
public:
    PyExact(const py::object& vertices, const py::object& faces, const py::object& axis)
        : axis_(textOption(axis, "axis")) {
        const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
        const vds::Axis a = vds::parseAxis(axis_);
        py::gil_scoped_release released;
        report_ = vds::validateMesh(mesh.view);
        exact_ = std::make_unique<vds::ExactClassifier>(mesh.view, a); // copies the triangles
        mesh_ = std::make_shared<MeshCopy>(mesh.view);
    }
    /// Pickled as what rebuilds it: (V, F, axis).
    py::tuple state() const {
        const py::tuple arrays = mesh_->arrays();
        return py::make_tuple(arrays[0], arrays[1], axis_);
    }
    BoolArray contains(const py::object& points, const py::object& rule, const py::object& threads) const {
        const vds::ClassifyOptions options = classifyOptions(rule, threads);
        warn(insideMessage(report_, "", options.rule));
        Points p = vds::python::viewPoints(points);
        BoolArray labels(py::ssize_t(p.count));
        auto* out = reinterpret_cast<std::uint8_t*>(labels.mutable_data());
        py::gil_scoped_release released;
        p.prepare(false);
        if (p.count) exact_->classify(p.points, out, options);
        return labels;
    }
    py::array_t<double> windingNumbers(const py::object& points) const {
        Points p = vds::python::viewPoints(points);
        py::array_t<double> numbers(py::ssize_t(p.count));
        double* out = numbers.mutable_data();
        py::gil_scoped_release released;
        p.prepare(false);
        for (std::size_t k = 0; k < p.count; ++k) out[k] = shownWinding(exact_->generalizedWinding(p.points[k]));
        return numbers;
    }
    std::size_t boundaryEdges() const { return exact_->boundaryEdgeCount(); }

private:
    std::string axis_;
    std::shared_ptr<const MeshCopy> mesh_;
    vds::MeshReport report_;
    std::unique_ptr<vds::ExactClassifier> exact_;
};


// ---- classifiers -----------------------------------------------------------

/// The built-in method `name` names (vds.methods()); a typo is told the
/// nearest name, and "custom" (a C++ classifier's method) is no choice here.
vds::Method parseMethod(const std::string& name) {
    std::vector<std::string> names;
    for (const vds::MethodInfo* m = vds::methodTable(); m != vds::methodTable() + vds::kMethodCount; ++m)
        if (m->builtIn()) names.push_back(m->name);
    if (std::find(names.begin(), names.end(), name) == names.end()) vds::throwUnknownName("method", name, names);
    return vds::parseEnum<vds::Method>(name);
}

/// vds.Classifier: any `Method`, made by vds::makeClassifier. A CPU method's
/// classifier is owned here; a GPU method's lives in GlState::classifiers
/// (it belongs to the module's context) under `glId`.
class PyClassifier {
public:
    /// From a mesh.
    PyClassifier(const py::object& vertices, const py::object& faces, const std::string& methodName,
                 const py::object& resolution, const std::string& axis, const std::string& bakeMethod,
                 const py::object& slices, const py::object& threads, const std::string& name)
        : method_(parseMethod(methodName)) {
        const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
        vds::MethodOptions options;
        options.resolution = vds::python::countOption(resolution, "resolution");
        options.bakeMethod = vds::parseBakeMethod(bakeMethod);
        options.slices = vds::python::countOption(slices, "slices");
        options.threads = vds::python::threadCount(threads);
        options.sourceName = name;
        const bool autoAxis = axis == "auto";
        if (!autoAxis) options.axis = vds::parseAxis(axis);
        name_ = name;
        rebuild_ = py::make_tuple(methodName, options.resolution, axis, bakeMethod, options.slices, options.threads, name);
        mesh_ = std::make_shared<MeshCopy>(mesh.view);
        {
            py::gil_scoped_release released;
            report_ = vds::validateMesh(mesh.view);
        }
        fromMesh_ = true;
        vds::requireUsable(report_, name);
        const vds::MethodInfo& info = vds::methodInfo(method_);
        py::gil_scoped_release released;
        // Sprites bake along the axis with the fewest layers when none is given
        // (MethodOptions); the certified bands take that axis too.
        if (autoAxis && method_ == vds::Method::Certified)
            options.axis = vds::chooseViewAxis(mesh.view, options.resolution ? options.resolution
                                                                             : info.defaultResolution).axis;
        const bool needsGl = info.layer != vds::Layer::Core ||
                             (method_ == vds::Method::Sprite && options.bakeMethod != vds::BakeMethod::Cpu);
        if (!needsGl) {
            adopt(vds::makeClassifier(mesh.view, method_, options));
            return;
        }
        glThread().run([&](GlState& s) { adopt(s, vds::makeClassifier(s.context(), mesh.view, method_, options)); });
    }

    /// From a sprite (copied: later transforms of `sprite` do not move it).
    PyClassifier(const PySprite& sprite, const std::string& methodName)
        : method_(parseMethod(methodName)) {
        spriteOpen_ = sprite.status != vds::SolidStatus::Closed;
        spriteValidation_ = sprite.validation;
        rebuild_ = py::make_tuple(methodName);
        py::gil_scoped_release released;
        vds::Sprite copy = static_cast<const vds::Sprite&>(sprite);
        sprite_ = std::make_shared<const vds::Sprite>(copy); // encoded only if pickled
        if (!vds::methodInfo(method_).gpu) {
            adopt(vds::makeClassifier(std::move(copy), method_));
            return;
        }
        glThread().run([&](GlState& s) { adopt(s, vds::makeClassifier(s.context(), std::move(copy), method_)); });
    }

    ~PyClassifier() {
        if (const std::uint64_t id = glId) glThread().post([id](GlState& s) { s.classifiers.erase(id); });
    }
    PyClassifier(const PyClassifier&) = delete;
    PyClassifier& operator=(const PyClassifier&) = delete;

    py::object classify(const py::object& points, const py::object& rule, const py::object& threads,
                        bool withStats) const {
        vds::ClassifyOptions options = classifyOptions(rule, threads);
        vds::requireRule(method_, options.rule);
        warnFor(options.rule);
        vds::ClassifyStats stats;
        options.stats = &stats;
        Points p = vds::python::viewPoints(points);
        BoolArray labels(py::ssize_t(p.count));
        auto* out = reinterpret_cast<std::uint8_t*>(labels.mutable_data());
        {
            py::gil_scoped_release released;
            p.prepare(false);
            if (p.count) run([&](const vds::Classifier& c) { c.classify(p.points, out, options); });
        }
        if (withStats) return py::make_tuple(labels, statsDict(stats));
        return std::move(labels);
    }

    BoolArray occupancy(const py::object& gridObject, const py::object& rule, const py::object& threads) const {
        const vds::Grid grid = gridFrom(gridObject);
        const vds::ClassifyOptions options = classifyOptions(rule, threads);
        vds::requireRule(method_, options.rule);
        warnFor(options.rule);
        BoolArray cells = vds::python::gridArray(grid);
        auto* out = reinterpret_cast<std::uint8_t*>(cells.mutable_data());
        py::gil_scoped_release released;
        run([&](const vds::Classifier& c) { c.occupancy(grid, out, options); });
        return cells;
    }

    /// Pickled as what rebuilds it: ("mesh", V, F, method, resolution, axis,
    /// bake_method, slices, threads, name) or ("sprite", .vds bytes, method).
    py::tuple state() const {
        if (mesh_) {
            const py::tuple arrays = mesh_->arrays();
            return py::make_tuple("mesh", arrays[0], arrays[1]) + rebuild_;
        }
        std::vector<char> bytes;
        {
            py::gil_scoped_release released;
            bytes = vds::encodeSprite(*sprite_);
        }
        return py::make_tuple("sprite", py::bytes(bytes.data(), bytes.size())) + rebuild_;
    }

    vds::Method method() const { return method_; }
    std::size_t memoryBytes() const { return memoryBytes_; }
    const std::string& summary() const { return summary_; }

private:
    /// Keeps a CPU method's classifier.
    void adopt(std::unique_ptr<vds::Classifier> classifier) {
        memoryBytes_ = classifier->memoryBytes();
        summary_ = classifier->summary();
        cpu_ = std::move(classifier);
    }
    /// On the GL thread: keeps a CPU method's classifier (built on GL), or
    /// files a GPU method's in the GL state.
    void adopt(GlState& s, std::unique_ptr<vds::Classifier> classifier) {
        if (!vds::methodInfo(method_).gpu) {
            adopt(std::move(classifier));
            return;
        }
        memoryBytes_ = classifier->memoryBytes();
        summary_ = classifier->summary();
        glId = nextGlId.fetch_add(1);
        s.classifiers.emplace(glId, std::move(classifier));
    }

    /// Calls `f` with the classifier: a CPU one here, a GPU one on the GL
    /// thread. Runs without the GIL.
    template <class F> void run(F&& f) const {
        if (cpu_) {
            f(*cpu_);
            return;
        }
        glThread().run([&](GlState& s) {
            const auto it = s.classifiers.find(glId);
            if (it == s.classifiers.end())
                throw vds::GlUnavailable(
                    "this GPU classifier's GL context was released (vds._release_gl); make it again");
            f(*it->second);
        });
    }

    /// The CLI's warning for a mesh (or sprite) that bounds no solid by `rule`.
    void warnFor(vds::Rule rule) const {
        if (fromMesh_) {
            warn(insideMessage(report_, name_, rule));
        } else if (spriteOpen_ && rule != vds::Rule::GeneralizedWinding) {
            warn(vds::openSpriteMessage(spriteValidation_, rule, pythonFlags()));
        }
    }

    vds::Method method_;
    std::unique_ptr<vds::Classifier> cpu_;
    std::uint64_t glId = 0;
    std::size_t memoryBytes_ = 0;
    std::string summary_;
    bool fromMesh_ = false;
    vds::MeshReport report_;
    std::string name_;
    bool spriteOpen_ = false;
    std::string spriteValidation_;
    // What rebuilds it (pickling): the mesh, or the sprite's bytes as given, and the arguments.
    std::shared_ptr<const MeshCopy> mesh_;
    std::shared_ptr<const vds::Sprite> sprite_;
    py::tuple rebuild_;
};

/// A classifier from its pickled `state()`.
PyClassifier* classifierFromState(const py::tuple& t) {
    if (t.size() == 3 && py::str(t[0]).cast<std::string>() == "sprite")
        return new PyClassifier(*spriteFromBytes(t[1].cast<py::bytes>(), "<pickle>"), t[2].cast<std::string>());
    if (t.size() != 10 || py::str(t[0]).cast<std::string>() != "mesh")
        throw vds::InvalidArgument("not a pickled vds.Classifier");
    return new PyClassifier(t[1], t[2], t[3].cast<std::string>(), t[4], t[5].cast<std::string>(),
                            t[6].cast<std::string>(), t[7], t[8], t[9].cast<std::string>());
}

py::list methodTable() {
    py::list methods;
    for (const vds::MethodInfo* m = vds::methodTable(); m != vds::methodTable() + vds::kMethodCount; ++m) {
        // Method::Custom names classifiers written outside the library: nothing Python can make.
        if (!m->builtIn()) continue;
        py::list rules;
        for (const auto& rule : vds::EnumNames<vds::Rule>::table)
            if (vds::answers(m->method, rule.value)) rules.append(rule.name);
        static const char* const layers[] = {"core", "gl", "voxel"};
        py::dict d;
        d["name"] = m->name;
        d["exact"] = m->exact;
        d["gpu"] = m->gpu;
        d["needs_closed_mesh"] = m->needsClosedMesh;
        d["from_sprite"] = m->fromSprite;
        d["rules"] = py::tuple(rules);
        d["default_resolution"] = m->defaultResolution;
        d["layer"] = layers[unsigned(m->layer)];
        d["summary"] = m->summary;
        methods.append(d);
    }
    return methods;
}

/// vds.Classifier.
void bindClassifier(py::module_& m) {
    py::class_<PyClassifier>(m, "Classifier", R"doc(
One way of answering "inside?" made ready for one solid: any method of
`vds.methods()` by its name, as the command line's `--method`.

    Classifier(V, F, method="sprite", *, resolution=0, axis="auto",
               bake_method="cpu", slices=0, threads=0, name="")
    Classifier(sprite, method="sprite")

V: (n, 3) float32/float64 vertex positions, F: (m, 3) integer vertex
indices, counter-clockwise seen from outside (float32 V and int32/uint32 F,
C-contiguous, are read in place; the classifier keeps what it needs, not
the arrays). method: "sprite", "exact", "certified", "sprite-gpu",
"certified-gpu", "slicemap", "slicemap-local", "solid", "solid-compute" or a
voxel method's "-gpu" form. resolution: texels (sprites, certified bands) or cells (voxel
grids) on the box's longest side, 0 for the method's default. axis: the view
axis of sprites and certified bands, "x", "y", "z" or "auto" (the fewest
layers). bake_method: how sprite methods bake ("cpu", "lists", "peel").
slices: slicemaps' slice count, 0 for the box depth in cells. threads: for
building. name: the mesh's name in messages.
From a Sprite (copied: its later transforms do not move this classifier),
methods "sprite" and "sprite-gpu" only.

GPU methods (and the GL bake methods and the voxel methods' builds) run on
the module's headless GL context; their calls from several threads take
turns. CPU methods may be used from any number of threads at once. Raises
vds.InvalidMesh for an unusable mesh (or an open one for the voxel
methods), vds.InvalidArgument for an unknown method or option, and
vds.GlUnavailable where a GL method finds no GL.)doc")
        .def(py::init<const PySprite&, const std::string&>(), py::arg("sprite"), py::arg("method") = "sprite")
        .def(py::init<const py::object&, const py::object&, const std::string&, const py::object&, const std::string&,
                      const std::string&, const py::object&, const py::object&, const std::string&>(),
             py::arg("V"), py::arg("F"), py::arg("method") = "sprite", py::kw_only(), py::arg("resolution") = 0,
             py::arg("axis") = "auto", py::arg("bake_method") = "cpu", py::arg("slices") = 0, py::arg("threads") = 0,
             py::arg("name") = "")
        .def("classify", &PyClassifier::classify, py::arg("points"), py::arg("rule") = "parity",
             py::arg("threads") = 0, py::arg("stats") = false, (std::string(R"doc(
Inside tests of points: (N, 3) float32 or float64 (any strides), mesh
coordinates -> (N,) bool, True inside.)doc") + kRuleDoc + R"doc(
    A method that cannot answer the rule raises vds.InvalidArgument (the
    voxel methods answer "parity" only: see vds.methods()).
threads: CPU threads, 0: one per hardware thread (GPU methods ignore it).
stats: if True, returns (labels, {"certain": n, "exact": m}): how many
    points the method answered itself and how many by the exact classifier
    (the certified method's fallback; 0 for the others).
Releases the GIL while it works.)doc").c_str())
        .def("contains", [](const PyClassifier& c, const py::object& points, const py::object& rule,
                            const py::object& threads) { return c.classify(points, rule, threads, false); },
             py::arg("points"), py::arg("rule") = "parity", py::arg("threads") = 0,
             "`classify` without stats (the name `Sprite` and `ExactClassifier` use).")
        .def("occupancy", &PyClassifier::occupancy, py::arg("grid"), py::arg("rule") = "parity",
             py::arg("threads") = 0, R"doc(
Labels every cell centre of `grid` (a vds.Grid): a bool array of shape
grid.shape, [i, j, k] True inside, equal to `classify(grid.cell_centres()
.reshape(-1, 3))` reshaped. Sprites (CPU and GPU) and the exact classifier
sweep columns; the other methods classify the centres.)doc")
        .def_property_readonly("method", [](const PyClassifier& c) { return vds::enumName(c.method()); },
                               "the method's name, as in vds.methods()")
        .def_property_readonly("memory_bytes", &PyClassifier::memoryBytes,
                               "bytes the queries read (host memory; a GPU method's GPU memory)")
        .def_property_readonly("summary", &PyClassifier::summary, "one line about what was built")
        .def("__repr__", [](const PyClassifier& c) { return "<vds.Classifier " + c.summary() + ">"; })
        .def(py::pickle([](const PyClassifier& c) { return c.state(); },
                        [](const py::tuple& t) { return std::unique_ptr<PyClassifier>(classifierFromState(t)); }));

}

/// vds.ExactClassifier.
void bindExact(py::module_& m) {
    py::class_<PyExact>(m, "ExactClassifier", R"doc(
The exact classifier on a mesh's triangles (exact predicates, no sprite).

V: (n, 3) float32/float64 vertex positions (kept as float32), F: (m, 3)
integer vertex indices, counter-clockwise seen from outside. The triangles
are copied; build once, ask many times (thread safe). The same labels as
Classifier(V, F, "exact").)doc")
        .def(py::init<const py::object&, const py::object&, const py::object&>(), py::arg("V"), py::arg("F"),
             py::arg("axis") = "z")
        .def("contains", &PyExact::contains, py::arg("points"), py::arg("rule") = "parity", py::arg("threads") = 0,
             (std::string("(N, 3) float points -> (N,) bool.") + kRuleDoc).c_str())
        .def("winding_numbers", &PyExact::windingNumbers, py::arg("points"),
             "(N, 3) float points -> (N,) float64 generalized winding numbers (1 inside a closed mesh, 0 outside); "
             "a tie with 1/2 (within 1e-9, a sheet's own points) is 1/2 exactly, so `> 0.5` is contains()'s label.")
        .def_property_readonly("boundary_edges", &PyExact::boundaryEdges,
                               "edges of the generalized winding number's boundary (edge uses that do not cancel, "
                               "counted with multiplicity): validate_mesh(V, F)[\"winding_boundary_edges\"], 0 for a "
                               "mesh without holes or orientation conflicts")
        .def(py::pickle([](const PyExact& e) { return e.state(); },
                        [](const py::tuple& t) {
                            if (t.size() != 3) throw vds::InvalidArgument("not a pickled vds.ExactClassifier");
                            return std::make_unique<PyExact>(t[0], t[1], t[2]);
                        }));

}

} // namespace

void bindClassifiers(py::module_& m) {
    bindClassifier(m);
    bindExact(m);
    m.def("_methods", &methodTable, "The method table as dicts (vds.methods() wraps them).");
}

} // namespace vds::python
