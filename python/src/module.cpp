// vds._vds: the compiled half of the Python module `vds` (pybind11, numpy).
//
// Points enter as numpy arrays of shape (N, 3), float32 or float64, and are
// read in place where the library can read them (float32 with x, y, z side by
// side, any row stride: the strided classify of <vds/sprite.h>); anything
// else is converted to packed float32 once. Labels are written straight into
// the numpy bool array returned. The GIL is released for the conversion,
// the finiteness check, classification and baking.
//
// GL (bake methods "lists" and "peel", contains(gpu=True)) runs on one
// headless context owned by the module, made lazily and used under a mutex
// by whichever thread calls. A sprite's GPU copy is made on its first
// contains(gpu=True) and kept in that state, keyed by the sprite, until the
// sprite is freed. All of it is released by `_release_gl`, which
// vds/__init__.py registers with Python's atexit: Python runs that while the
// interpreter finalizes, before the C library's exit handlers (EGL's among
// them). The state itself is never destroyed by a static destructor.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <utility>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <glm/mat4x4.hpp>

#include <vds/all.h>
#include <vds/bake.h>
#include <vds/error.h>
#include <vds/exact.h>
#include <vds/gl/context.h>
#include <vds/gl/sprite.h>
#include <vds/mesh_io.h>
#include <vds/sprite.h>
#include <vds/vds_file.h>

namespace py = pybind11;

namespace {

using BoolArray = py::array_t<bool, py::array::c_style>;

std::string fspath(const py::object& path) {
    return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

std::string shapeText(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

// ---- points --------------------------------------------------------------

/// An (N, 3) array's points as the library reads them: three floats side by
/// side every `stride` bytes from `xyz`, either the caller's own memory or
/// `packed`. `source` keeps the caller's array alive.
struct Points {
    py::array source;
    const char* data = nullptr;
    py::ssize_t rowStride = 0, columnStride = 0;
    bool isDouble = false;
    std::size_t count = 0;
    std::vector<glm::vec3> packed;
    const float* xyz = nullptr;
    std::size_t stride = sizeof(glm::vec3);

    bool inPlace() const {
        return !isDouble && columnStride == sizeof(float) && rowStride >= py::ssize_t(3 * sizeof(float)) &&
               rowStride % py::ssize_t(sizeof(float)) == 0 && reinterpret_cast<std::uintptr_t>(data) % alignof(float) == 0;
    }

    double at(std::size_t row, int column) const {
        const char* p = data + py::ssize_t(row) * rowStride + column * columnStride;
        if (isDouble) {
            double v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }
        float v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }

    /// Checks every coordinate and reads the points in place or packs them.
    /// `packedNeeded`: the caller needs glm::vec3 rows (the GPU path). Runs
    /// without the GIL; throws py::value_error for a non-finite coordinate.
    void prepare(bool packedNeeded) {
        const bool direct = inPlace() && (!packedNeeded || rowStride == py::ssize_t(sizeof(glm::vec3)));
        if (!direct) packed.resize(count);
        for (std::size_t k = 0; k < count; ++k) {
            const double x = at(k, 0), y = at(k, 1), z = at(k, 2);
            // A float64 beyond float's range would become infinite: refuse it too.
            if (!std::isfinite(float(x)) || !std::isfinite(float(y)) || !std::isfinite(float(z)))
                throw py::value_error("points[" + std::to_string(k) + "] = (" + std::to_string(x) + ", " +
                                      std::to_string(y) + ", " + std::to_string(z) +
                                      ") is not finite (or does not fit a float32)");
            if (!direct) packed[k] = glm::vec3(float(x), float(y), float(z));
        }
        if (direct) {
            xyz = reinterpret_cast<const float*>(data);
            stride = std::size_t(rowStride);
        } else {
            xyz = &packed.data()->x;
            stride = sizeof(glm::vec3);
        }
    }
    const glm::vec3* vec3() const { return reinterpret_cast<const glm::vec3*>(xyz); }
};

/// Inspects `object` (with the GIL): an (N, 3) array of float32 or float64;
/// integers are converted to float64, anything else refused.
Points viewPoints(const py::object& object, const char* what = "points") {
    Points p;
    p.source = py::array::ensure(object);
    if (!p.source) throw py::value_error(std::string(what) + " must be an (N, 3) numpy array of float32 or float64");
    // Native float32 and float64 are read as they are; integers, other
    // floats and other byte orders are converted to float64 first.
    const py::dtype type = p.source.dtype();
    const char kind = type.kind();
    const bool native = type.attr("isnative").cast<bool>();
    if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
        throw py::value_error(std::string(what) + " must be float32 or float64, not " + py::str(py::handle(type)).cast<std::string>());
    if (kind != 'f' || !native || (type.itemsize() != 4 && type.itemsize() != 8))
        p.source = py::array_t<double, py::array::forcecast>::ensure(p.source);
    if (p.source.ndim() != 2 || p.source.shape(1) != 3)
        throw py::value_error(std::string(what) + " must have shape (N, 3), not " + shapeText(p.source));
    p.isDouble = p.source.dtype().itemsize() == 8;
    p.data = static_cast<const char*>(p.source.data());
    p.rowStride = p.source.strides(0);
    p.columnStride = p.source.strides(1);
    p.count = std::size_t(p.source.shape(0));
    return p;
}

// ---- meshes --------------------------------------------------------------

/// V (n, 3) and F (m, 3) as the library's mesh (copied: float32 positions,
/// uint32 indices). Indices are checked against n here; geometry is judged
/// by the call that receives the mesh.
vds::TriangleMesh meshFrom(const py::object& vertices, const py::object& faces) {
    vds::TriangleMesh mesh;
    Points v = viewPoints(vertices, "V");
    auto f = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(faces);
    if (!f) throw py::value_error("F must be an (M, 3) integer array");
    if (f.ndim() != 2 || f.shape(1) != 3) throw py::value_error("F must have shape (M, 3), not " + shapeText(f));
    mesh.positions.resize(v.count);
    for (std::size_t k = 0; k < v.count; ++k)
        mesh.positions[k] = glm::vec3(float(v.at(k, 0)), float(v.at(k, 1)), float(v.at(k, 2)));
    const auto idx = f.unchecked<2>();
    mesh.triangles.resize(std::size_t(f.shape(0)));
    for (py::ssize_t t = 0; t < f.shape(0); ++t) {
        for (int c = 0; c < 3; ++c) {
            const std::int64_t i = idx(t, c);
            if (i < 0 || std::uint64_t(i) >= v.count)
                throw py::value_error("F[" + std::to_string(t) + ", " + std::to_string(c) + "] = " + std::to_string(i) +
                                      " is not a vertex index (V has " + std::to_string(v.count) + " rows)");
            mesh.triangles[std::size_t(t)][c] = std::uint32_t(i);
        }
    }
    return mesh;
}

py::tuple meshArrays(const vds::TriangleMesh& mesh) {
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

// ---- GL ------------------------------------------------------------------

/// The module's GL context and GPU classifier, made on first use, and the
/// sprites resident on it. Allocated once and never destroyed (no static
/// destructor may touch GL).
struct GlState {
    /// Guards every GL call, the context and `resident`.
    std::mutex mutex;
    std::unique_ptr<vds::GlContext> gl;
    std::unique_ptr<vds::GpuClassifier> classifier;
    /// GPU copies of Python sprites (`PySprite::gpuId`), kept between
    /// contains(gpu=True) calls; released with the context.
    std::unordered_map<std::uint64_t, std::unique_ptr<vds::GpuSprite>> resident;
    std::uint64_t nextId = 1; // under `mutex`

    /// Ids of sprites freed while `mutex` was held by another thread: their
    /// copies are freed by the next holder of `mutex`.
    std::mutex orphansMutex;
    std::vector<std::uint64_t> orphans;

    /// The context, made if need be; the caller holds `mutex`. Current on no
    /// thread between calls.
    const vds::GlContext& context() {
        if (!gl) {
            const vds::CurrentContext restore; // GlContext() makes itself current: undo that on return
            gl = std::make_unique<vds::GlContext>();
        }
        return *gl;
    }

    /// Frees the copies of sprites freed meanwhile. The caller holds `mutex`
    /// and has the context current (or there is none: then nothing is resident).
    void freeOrphans() {
        std::vector<std::uint64_t> ids;
        {
            const std::lock_guard<std::mutex> lock(orphansMutex);
            ids.swap(orphans);
        }
        for (const std::uint64_t id : ids) resident.erase(id);
    }
};

GlState& glState() {
    static GlState* state = new GlState; // leaked on purpose, see above
    return *state;
}

void releaseGl() {
    py::gil_scoped_release released;
    GlState& s = glState();
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (!s.gl) return;
    {
        const vds::CurrentContext scope(*s.gl);
        s.freeOrphans();
        s.resident.clear();
        s.classifier.reset();
    }
    s.gl.reset();
}

/// The Python Sprite: a vds::Sprite and the key of its GPU copy in
/// GlState::resident (0: none yet). The copy is owned by the module's GL
/// state, so `_release_gl` frees it with the context; a sprite freed later
/// finds nothing resident and calls no GL.
struct PySprite : vds::Sprite {
    explicit PySprite(vds::Sprite&& sprite) : vds::Sprite(std::move(sprite)) {}
    PySprite(const PySprite&) = delete;
    PySprite& operator=(const PySprite&) = delete;
    ~PySprite() { releaseGpu(); }

    std::uint64_t gpuId = 0;

    /// Frees the GPU copy, if any, under the GL mutex. Never blocks (Python
    /// may free a sprite on any thread, holding the GIL, while another thread
    /// classifies under the mutex): if the mutex is taken, the copy is left
    /// to its holder (GlState::orphans).
    void releaseGpu() noexcept {
        if (!gpuId) return;
        GlState& s = glState();
        const std::uint64_t id = std::exchange(gpuId, 0);
        try {
            std::unique_lock<std::mutex> lock(s.mutex, std::try_to_lock);
            if (!lock) {
                const std::lock_guard<std::mutex> orphansLock(s.orphansMutex);
                s.orphans.push_back(id);
                return;
            }
            const auto it = s.resident.find(id);
            if (it == s.resident.end() || !s.gl) return; // released with the context
            const vds::CurrentContext scope(*s.gl);
            s.resident.erase(it);
            s.freeOrphans();
        } catch (...) {
            // A context that cannot be made current: leave the copy to _release_gl.
        }
    }
};

std::shared_ptr<PySprite> wrap(vds::Sprite&& sprite) { return std::make_shared<PySprite>(std::move(sprite)); }

// ---- classification ------------------------------------------------------

BoolArray spriteContains(PySprite& sprite, const py::object& points, const std::string& ruleName, bool gpu,
                         unsigned threads) {
    vds::ClassifyOptions options;
    options.rule = vds::parseRule(ruleName);
    options.threads = threads;
    Points p = viewPoints(points);
    BoolArray labels(py::ssize_t(p.count));
    auto* out = reinterpret_cast<std::uint8_t*>(labels.mutable_data());
    py::gil_scoped_release released;
    p.prepare(gpu);
    if (p.count == 0) return labels;
    if (!gpu) {
        vds::classify(sprite, vds::PointsView::floats(p.xyz, p.count, p.stride), out, options);
        return labels;
    }
    GlState& s = glState();
    const std::lock_guard<std::mutex> lock(s.mutex);
    const vds::CurrentContext scope(s.context());
    s.freeOrphans();
    if (!s.classifier) s.classifier = std::make_unique<vds::GpuClassifier>(*s.gl);
    // The sprite's resident copy, uploaded on its first GPU call (or the first
    // after _release_gl); transform() changes only the placement, set here.
    auto it = sprite.gpuId ? s.resident.find(sprite.gpuId) : s.resident.end();
    if (it == s.resident.end()) {
        auto copy = std::make_unique<vds::GpuSprite>(sprite);
        if (!sprite.gpuId) sprite.gpuId = s.nextId++;
        it = s.resident.emplace(sprite.gpuId, std::move(copy)).first;
    }
    it->second->setPlacement(sprite.grid);
    s.classifier->classify(*it->second, vds::PointsView(p.vec3(), p.count), out, options);
    return labels;
}

std::shared_ptr<PySprite> bakeMesh(const py::object& vertices, const py::object& faces, std::uint32_t resolution,
                     const std::string& axis, const std::string& method, const std::string& name) {
    const vds::TriangleMesh mesh = meshFrom(vertices, faces);
    vds::BakeOptions options;
    options.resolution = resolution;
    options.method = vds::parseBakeMethod(method);
    options.sourceName = name;
    const bool autoAxis = axis == "auto";
    if (!autoAxis) options.axis = vds::parseAxis(axis);
    py::gil_scoped_release released;
    if (autoAxis) options.axis = vds::chooseViewAxis(mesh, options.resolution).axis;
    if (options.method == vds::BakeMethod::Cpu) return wrap(vds::bake(mesh, options));
    GlState& s = glState();
    const std::lock_guard<std::mutex> lock(s.mutex);
    return wrap(vds::bake(s.context(), mesh, options));
}

std::shared_ptr<PySprite> spriteFromBytes(const py::bytes& data, const std::string& name) {
    const std::string_view view(data);
    py::gil_scoped_release released;
    return wrap(vds::decodeSprite(view.data(), view.size(), name));
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
        throw py::value_error("matrix must have shape (4, 4)");
    glm::mat4 model(1.0f);
    const auto a = m.unchecked<2>();
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) {
            if (!std::isfinite(a(row, column))) throw py::value_error("matrix has a non-finite entry");
            model[column][row] = float(a(row, column)); // glm is column-major
        }
    return model;
}

class PyExact {
public:
    PyExact(const py::object& vertices, const py::object& faces, const std::string& axis)
        : mesh_(meshFrom(vertices, faces)) {
        const vds::Axis a = vds::parseAxis(axis);
        py::gil_scoped_release released;
        exact_ = std::make_unique<vds::ExactClassifier>(mesh_, a);
    }
    BoolArray contains(const py::object& points, const std::string& ruleName, unsigned threads) const {
        vds::ClassifyOptions options;
        options.rule = vds::parseRule(ruleName);
        options.threads = threads;
        Points p = viewPoints(points);
        BoolArray labels(py::ssize_t(p.count));
        auto* out = reinterpret_cast<std::uint8_t*>(labels.mutable_data());
        py::gil_scoped_release released;
        p.prepare(false);
        if (p.count) exact_->classify(vds::PointsView::floats(p.xyz, p.count, p.stride), out, options);
        return labels;
    }
    py::array_t<double> windingNumbers(const py::object& points) const {
        Points p = viewPoints(points);
        py::array_t<double> numbers(py::ssize_t(p.count));
        double* out = numbers.mutable_data();
        py::gil_scoped_release released;
        p.prepare(true);
        for (std::size_t k = 0; k < p.count; ++k) out[k] = exact_->generalizedWinding(p.vec3()[k]);
        return numbers;
    }
    std::size_t boundaryEdges() const { return exact_->boundaryEdgeCount(); }

private:
    vds::TriangleMesh mesh_;
    std::unique_ptr<vds::ExactClassifier> exact_;
};

void registerExceptions(py::module_& m) {
    // Most specific last: pybind11 tries the translators registered last first.
    py::register_exception<vds::Error>(m, "Error", PyExc_RuntimeError);
    py::register_exception<vds::IoError>(m, "IoError", PyExc_OSError);
    py::register_exception<vds::FormatError>(m, "FormatError", PyExc_ValueError);
    py::register_exception<vds::InvalidMesh>(m, "InvalidMesh", PyExc_ValueError);
    py::register_exception<vds::GlUnavailable>(m, "GlUnavailable", PyExc_RuntimeError);
    py::register_exception<vds::GlError>(m, "GlError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr e) {
        try {
            if (e) std::rethrow_exception(e);
        } catch (const vds::InvalidArgument& error) {
            PyErr_SetString(PyExc_ValueError, error.what());
        } catch (const vds::OutOfMemory& error) {
            PyErr_SetString(PyExc_MemoryError, error.what());
        }
    });
}

} // namespace

PYBIND11_MODULE(_vds, m) {
    m.doc() = "vds: point-in-solid tests with volumetric depth sprites (the compiled part; use `import vds`)";
    registerExceptions(m);

    py::class_<PySprite, std::shared_ptr<PySprite>>(m, "Sprite", R"doc(
A volumetric depth sprite: a closed mesh baked into layered depth columns.

Made by `vds.bake`, `vds.read` or `vds.from_bytes`. Answers inside/outside
for points in the mesh's coordinates (after any `transform`). Classifying is
thread safe; `transform` must not run while another thread classifies.
Pickles as its .vds file bytes.)doc")
        .def("contains", &spriteContains, py::arg("points"), py::arg("rule") = "parity", py::arg("gpu") = false,
             py::arg("threads") = 0, R"doc(
Inside tests of points.

points: (N, 3) float32 or float64 array (any strides; float32 with x, y, z
    adjacent is read in place), world coordinates: the mesh's units, moved
    by `transform`. Points outside the sprite's box are outside.
rule: "parity" (odd crossings in front), "winding" (non-zero winding) or
    "generalized-winding" (for sprites of closed meshes).
gpu: classify with the GL compute shader on the module's headless context
    (answers identical to the CPU's; for "generalized-winding" on an open
    mesh the boundary term is summed in float, which can flip a label where
    the winding number is within float error, up to about 1e-4 near the
    holes' rims, of 1/2). The sprite is
    uploaded on its first gpu=True call and stays resident on the GPU until
    it is freed (or vds._release_gl runs at exit); `transform` only moves
    it. Calls from several threads take turns.
threads: CPU threads, 0: one per hardware thread.
Returns a (N,) bool array, True inside. Raises ValueError for another shape,
dtype or a non-finite coordinate. Releases the GIL while it works.)doc")
        .def("transform", [](PySprite& s, const py::object& matrix) { s.transform(matrixFrom(matrix)); },
             py::arg("matrix"), R"doc(
Moves the sprite by a (4, 4) affine, invertible matrix (row-major, acting on
column vectors [x, y, z, 1]), on top of its current placement, without
re-baking: a sprite of solid S answers for matrix(S) afterwards.)doc")
        .def("save", [](const PySprite& s, const py::object& path) {
                 const std::string p = fspath(path);
                 py::gil_scoped_release released;
                 vds::writeSprite(s, p);
             }, py::arg("path"), "Writes the sprite as a .vds file, atomically (temporary file, then rename).")
        .def("to_bytes", &spriteBytes, "The bytes of the sprite's .vds file (what `save` writes).")
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
        .def_property_readonly("status", [](const PySprite& s) {
                 return s.status == vds::SolidStatus::Closed ? "closed" : "open";
             }, "\"closed\" (the mesh bounds a solid) or \"open\" (holes or orientation conflicts: a surface's answers)")
        .def_property_readonly("validation", [](const PySprite& s) { return s.validation; },
                               "the mesh validation summary recorded at bake time")
        .def_property_readonly("axis", [](const PySprite& s) { return vds::toString(s.grid.axis); },
                               "the view axis, \"x\", \"y\" or \"z\"")
        .def_property_readonly("source_name", [](const PySprite& s) { return s.sourceName; })
        .def_property_readonly("memory_bytes", &vds::Sprite::memoryBytes, "bytes of host memory the layers take")
        .def("__repr__", [](const PySprite& s) {
            return "<vds.Sprite " + std::to_string(s.width()) + "x" + std::to_string(s.height()) + ", " +
                   std::to_string(s.depthComplexity) + " layers, axis " + vds::toString(s.grid.axis) + ", " +
                   (s.status == vds::SolidStatus::Closed ? "closed" : "open") +
                   (s.sourceName.empty() ? "" : ", from " + s.sourceName) + ">";
        })
        .def(py::pickle([](const PySprite& s) { return spriteBytes(s); },
                        [](const py::bytes& b) { return spriteFromBytes(b, "<pickle>"); }));

    py::class_<PyExact>(m, "ExactClassifier", R"doc(
The exact classifier on a mesh's triangles (exact predicates, no sprite).

V: (n, 3) float array of vertex positions (kept as float32), F: (m, 3)
integer array of vertex indices, counter-clockwise seen from outside. The
triangles are copied; build once, ask many times (thread safe).)doc")
        .def(py::init<const py::object&, const py::object&, const std::string&>(), py::arg("V"), py::arg("F"),
             py::arg("axis") = "z")
        .def("contains", &PyExact::contains, py::arg("points"), py::arg("rule") = "parity", py::arg("threads") = 0,
             "(N, 3) float points -> (N,) bool, by \"parity\", \"winding\" or \"generalized-winding\".")
        .def("winding_numbers", &PyExact::windingNumbers, py::arg("points"),
             "(N, 3) float points -> (N,) float64 generalized winding numbers (1 inside a closed mesh, 0 outside).")
        .def_property_readonly("boundary_edges", &PyExact::boundaryEdges,
                               "edges whose uses do not cancel: 0 for a mesh that bounds a solid");

    m.def("bake", &bakeMesh, py::arg("V"), py::arg("F"), py::arg("resolution") = 1024, py::arg("axis") = "auto",
          py::arg("method") = "lists", py::arg("name") = "", R"doc(
Bakes a triangle mesh into a Sprite.

V: (n, 3) float array of vertex positions (mesh units; kept as float32).
F: (m, 3) integer array of vertex indices, counter-clockwise seen from outside.
resolution: texels on the longer side of the view, 1..16384.
axis: "x", "y", "z", or "auto" (the axis with the fewest layers).
method: "lists" (GL fragment lists, the default), "peel" (GL depth peeling)
    or "cpu" (exact ray casting, no GL).
Raises vds.InvalidMesh for an unusable mesh (empty, non-finite, bad
indices); an open mesh is baked with status "open". GL methods raise
vds.GlUnavailable where no GL context can be had. Releases the GIL.)doc");
    m.def("load_mesh", [](const py::object& path) {
              const std::string p = fspath(path);
              vds::TriangleMesh mesh;
              {
                  py::gil_scoped_release released;
                  mesh = vds::loadMesh(p);
              }
              return meshArrays(mesh);
          }, py::arg("path"), R"doc(
Reads an OBJ, PLY, STL or OFF mesh: returns (V, F), V a (n, 3) float64 array
of positions in the file's units, F a (m, 3) int32 array of vertex indices
(polygons fanned into triangles). Raises vds.IoError (an OSError) for a file
that cannot be read, vds.FormatError (a ValueError) for a malformed one.)doc");
    m.def("read", [](const py::object& path) {
              const std::string p = fspath(path);
              py::gil_scoped_release released;
              return wrap(vds::readSprite(p));
          }, py::arg("path"),
          "Reads a .vds file. Raises vds.IoError (an OSError) if it cannot be read, vds.FormatError (a ValueError) if it is not a valid .vds file.");
    m.def("from_bytes", &spriteFromBytes, py::arg("data"), py::arg("name") = "<memory>",
          "The Sprite whose .vds file bytes are `data` (see Sprite.to_bytes). Raises vds.FormatError for bad bytes.");
    m.def("gl_available", [] {
              std::string reason;
              const bool ok = vds::glAvailable(&reason);
              return py::make_tuple(ok, reason);
          }, "(bool, reason): whether a headless GL context can be had here, and why not.");
    m.def("_gpu_resident", [] {
              py::gil_scoped_release released;
              GlState& s = glState();
              const std::lock_guard<std::mutex> lock(s.mutex);
              std::size_t orphans;
              {
                  const std::lock_guard<std::mutex> orphansLock(s.orphansMutex);
                  orphans = s.orphans.size();
              }
              return s.resident.size() - std::min(orphans, s.resident.size());
          }, "How many sprites have a GPU copy resident on the module's context (for tests).");
    m.def("_release_gl", &releaseGl, "Frees the module's GL context (registered with atexit by vds/__init__.py).");
}
