// vds._vds: the compiled half of the Python module `vds` (pybind11, numpy).
//
// Every method of the library's one contract (<vds/classify.h>) is reachable
// by its `Method` name through `Classifier` (made by `vds::makeClassifier`,
// <vds/all.h>), every grid through `Grid` and the occupancy calls; numpy
// arrays enter through arrays.h (in place where their layout allows) and
// labels are written straight into the numpy bool array returned. The GIL is
// released for the conversion, the finiteness check, classification, sweeps
// and building.
//
// GL (bake methods "lists" and "peel", gpu=True, the GPU and voxel methods)
// runs on one headless context owned by the module, made lazily on one
// thread of the module's (`GlThread`) that runs every GL call in turn, for
// whichever Python thread asks: GL objects belong to the thread and context
// they were made on. A sprite's GPU copy is made on its first gpu=True call
// and kept there, keyed by the sprite, until the sprite is freed; GPU
// classifiers live there too. All of it is released, and the thread stopped,
// by `_release_gl`, which vds/__init__.py registers with Python's atexit:
// Python runs that while the interpreter finalizes, before the C library's
// exit handlers (EGL's among them). Nothing is destroyed by a static
// destructor.
//
// Errors: every vds::Error becomes the vds exception of the same name, each a
// subclass of vds.Error (and of the builtin class its kind fits: OSError,
// ValueError, MemoryError, RuntimeError); see registerExceptions.
#include <pthread.h>

#include <string>

#include <pybind11/pybind11.h>

#include <vds/all.h>
#include <vds/error.h>
#include <vds/mesh_check.h>

#include "arrays.h"
#include "bindings.h"
#include "distance.h"

namespace py = pybind11;
using vds::python::DTypeError;

namespace vds::python {

// ---- warnings --------------------------------------------------------------

PyObject* meshWarning = nullptr;

const vds::MeshFlags& pythonFlags() {
    // Python answers a mesh that bounds no solid anyway, with the warning: no allow-open flag to name.
    static const vds::MeshFlags flags{"rule=\"generalized-winding\"", ""};
    return flags;
}

std::string insideMessage(const vds::MeshReport& report, const std::string& name, vds::Rule rule) {
    const std::string open = vds::openMeshMessage(report, name, rule, pythonFlags());
    if (!open.empty()) return open + "; answered anyway";
    return vds::insideWarning(report, rule, pythonFlags());
}

namespace {

/// The folder of the vds package (where _vds and __init__.py lie), with a
/// trailing slash; "" where it cannot be told.
const std::string& packageFolder() {
    static const std::string folder = [] {
        try {
            const std::string file = py::module_::import("vds._vds").attr("__file__").cast<std::string>();
            return file.substr(0, file.rfind('/') + 1);
        } catch (const py::error_already_set&) {
            return std::string();
        }
    }();
    return folder;
}

/// The stack level of the first frame outside the vds package: where the
/// user's code called in (1: the caller of the compiled function).
int callerStackLevel() {
    const std::string& folder = packageFolder();
    int level = 1;
    if (folder.empty()) return level;
    PyFrameObject* frame = PyEval_GetFrame(); // borrowed
    Py_XINCREF(frame);
    while (frame) {
        PyCodeObject* code = PyFrame_GetCode(frame);
        const std::string file = py::reinterpret_borrow<py::object>(code->co_filename).cast<std::string>();
        Py_DECREF(code);
        if (file.rfind(folder, 0) != 0) break;
        ++level;
        PyFrameObject* back = PyFrame_GetBack(frame);
        Py_DECREF(frame);
        frame = back;
    }
    Py_XDECREF(frame);
    return level;
}

} // namespace

void warn(const std::string& message) {
    if (message.empty()) return;
    if (PyErr_WarnEx(meshWarning, message.c_str(), callerStackLevel()) < 0) throw py::error_already_set();
}

void warnOpenSprite(const vds::Sprite& sprite, vds::Rule rule) {
    if (sprite.status != vds::SolidStatus::Closed && rule != vds::Rule::GeneralizedWinding)
        warn(vds::openSpriteMessage(sprite.validation, rule, pythonFlags()));
}

// ---- options ---------------------------------------------------------------

vds::ClassifyOptions classifyOptions(const py::object& rule, const py::object& threads) {
    vds::ClassifyOptions options;
    options.rule = vds::parseRule(textOption(rule, "rule"));
    options.threads = vds::python::threadCount(threads);
    return options;
}

py::dict statsDict(const vds::ClassifyStats& stats) {
    py::dict d;
    d["certain"] = stats.certain;
    d["exact"] = stats.exact;
    return d;
}

extern const char* const kRuleDoc;
const char* const kRuleDoc = R"doc(
rule: "parity" (odd crossings in front), "winding" (non-zero winding) or
    "generalized-winding" (the generalized winding number above 1/2: defined
    for open meshes and soups too). A mesh that bounds no solid by the rule
    asked gets a vds.MeshWarning, with the command-line tool's text.)doc";


namespace {

// ---- errors ----------------------------------------------------------------

/// One Python class per vds error class, each a vds.Error.
struct ErrorClasses {
    PyObject* error = nullptr;
    PyObject* ioError = nullptr;
    PyObject* formatError = nullptr;
    PyObject* invalidArgument = nullptr;
    PyObject* dtypeError = nullptr;
    PyObject* invalidMesh = nullptr;
    PyObject* glUnavailable = nullptr;
    PyObject* glError = nullptr;
    PyObject* outOfMemory = nullptr;
};
ErrorClasses errors; // set once by the module's init, never freed (the module holds them too)

PyObject* newClass(py::module_& m, const char* name, std::initializer_list<PyObject*> bases, const char* doc) {
    py::tuple b(bases.size());
    std::size_t k = 0;
    for (PyObject* base : bases) b[k++] = py::reinterpret_borrow<py::object>(base);
    const std::string qualified = std::string("vds.") + name;
    PyObject* c = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, b.ptr(), nullptr);
    if (!c) throw py::error_already_set();
    m.add_object(name, py::reinterpret_borrow<py::object>(c));
    return c; // one reference kept for `errors`
}

} // namespace

void registerExceptions(py::module_& m) {
    ErrorClasses& e = errors;
    e.error = newClass(m, "Error", {PyExc_Exception}, "Base of every exception vds raises.");
    e.ioError = newClass(m, "IoError", {e.error, PyExc_OSError},
                         "A file could not be opened, read, written or renamed (also an OSError).");
    e.formatError = newClass(m, "FormatError", {e.error, PyExc_ValueError},
                             "A file was read but is truncated, corrupt or inconsistent (also a ValueError).");
    e.invalidArgument = newClass(m, "InvalidArgument", {e.error, PyExc_ValueError},
                                 "An argument out of range: shape, value, option name (also a ValueError).");
    e.dtypeError = newClass(m, "DTypeError", {e.invalidArgument, PyExc_TypeError},
                            "An array of the wrong element type: points that are not float32/float64, faces that "
                            "are not integers (an InvalidArgument and a TypeError).");
    e.invalidMesh = newClass(m, "InvalidMesh", {e.error, PyExc_ValueError},
                             "A mesh that cannot be processed: empty, non-finite, bad face indices, or open where "
                             "a solid is needed (also a ValueError).");
    e.glUnavailable = newClass(m, "GlUnavailable", {e.error, PyExc_RuntimeError},
                               "No OpenGL 4.3 context could be had (also a RuntimeError).");
    e.glError = newClass(m, "GlError", {e.error, PyExc_RuntimeError},
                         "A GL call or shader failed (also a RuntimeError).");
    e.outOfMemory = newClass(m, "OutOfMemory", {e.error, PyExc_MemoryError},
                             "A request needs more memory than can be had (also a MemoryError).");
    meshWarning = PyErr_NewExceptionWithDoc(
        "vds.MeshWarning",
        "A mesh (or a sprite's mesh) that bounds no solid by the rule asked: open, non-manifold or "
        "inconsistently oriented. The text is the command-line tool's.",
        PyExc_UserWarning, nullptr);
    if (!meshWarning) throw py::error_already_set();
    m.add_object("MeshWarning", py::reinterpret_borrow<py::object>(meshWarning));

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const DTypeError& x) {
            PyErr_SetString(errors.dtypeError, x.what());
        } catch (const vds::IoError& x) {
            PyErr_SetString(errors.ioError, x.what());
        } catch (const vds::FormatError& x) {
            PyErr_SetString(errors.formatError, x.what());
        } catch (const vds::InvalidArgument& x) {
            PyErr_SetString(errors.invalidArgument, x.what());
        } catch (const vds::InvalidMesh& x) {
            PyErr_SetString(errors.invalidMesh, x.what());
        } catch (const vds::GlUnavailable& x) {
            PyErr_SetString(errors.glUnavailable, x.what());
        } catch (const vds::GlError& x) {
            PyErr_SetString(errors.glError, x.what());
        } catch (const vds::OutOfMemory& x) {
            PyErr_SetString(errors.outOfMemory, x.what());
        } catch (const vds::Error& x) {
            PyErr_SetString(errors.error, x.what());
        }
    });
}


} // namespace vds::python

PYBIND11_MODULE(_vds, m) {
    using namespace vds::python;
    m.doc() = "vds: point-in-solid tests with volumetric depth sprites (the compiled part; use `import vds`)";
    registerExceptions(m);
    vds::python::registerDistance(m);
    vds::python::registerVdb(m);
    pthread_atfork(nullptr, nullptr, &forgetGlThreadInChild);
    bindGrid(m);
    bindSprite(m);
    bindClassifiers(m);
    bindMeshFunctions(m);
    m.attr("__version__") = VDS_VERSION;
    m.def("gl_available", [] { return !glLostInFork && vds::glAvailable(); },
          "True where a headless GL context can be had here (gpu=True, the GL bake and GPU methods work); "
          "vds.gl_unavailable_reason() says why not.");
    m.def("gl_unavailable_reason", []() -> std::string {
              if (glLostInFork) return kLostInFork;
              std::string reason;
              return vds::glAvailable(&reason) ? std::string() : reason;
          }, "Why no headless GL context can be had here, in one line; \"\" where one can (vds.gl_available()).");
    m.def("_gpu_resident", [] {
              py::gil_scoped_release released;
              std::size_t count = 0;
              if (glThread().running()) glThread().run([&](GlState& s) { count = s.resident.size(); });
              return count;
          }, "How many sprites have a GPU copy resident on the module's context (for tests).");
    m.def("_release_gl", &releaseGl, "Frees the module's GL context (registered with atexit by vds/__init__.py).");
}
