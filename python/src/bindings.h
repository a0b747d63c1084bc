// vds._vds's internal parts, shared by its source files: the warnings and
// options every binding uses, the Python Sprite, and one function per topic
// that adds its classes and functions to the module.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <glm/vec3.hpp>

#include "arrays.h"

#include <vds/all.h>
#include <vds/mesh_check.h>

#include "gl_thread.h"

namespace vds::python {

namespace py = pybind11;

using BoolArray = py::array_t<bool, py::array::c_style>;

/// vds.MeshWarning, set by the module's init.
extern PyObject* meshWarning;

/// What the library says about a usable mesh and `rule`, in Python's words
/// (`pythonFlags`): the message of `requireInsideDefined` where inside is not
/// defined by the rule, else `insideWarning`'s; empty when there is nothing to say.
std::string insideMessage(const vds::MeshReport& report, const std::string& name, vds::Rule rule);
/// warnings.warn(message, vds.MeshWarning) at the caller's line (the first
/// frame outside the vds package); needs the GIL.
void warn(const std::string& message);
/// vds.MeshWarning where `rule` does not define the mesh's inside (as
/// vds.exact_contains warns), at the caller's line (python/src/distance.cpp).
void warnIfOpen(const MeshView& mesh, Rule rule);
/// The warning of a sprite baked from a mesh that bounds no solid (or is
/// mis-oriented), asked by a rule that answers for solids.
void warnOpenSprite(const vds::Sprite& sprite, vds::Rule rule);
/// How Python spells what the messages name: rule="generalized-winding".
const vds::MeshFlags& pythonFlags();

vds::ClassifyOptions classifyOptions(const py::object& rule, const py::object& threads);
py::dict statsDict(const vds::ClassifyStats& stats);
py::tuple tuple3(const glm::vec3& v);

extern const char* const kRuleDoc;

/// A generalized winding number as Python returns it: a tie (within
/// vds::kGeneralizedWindingTie of 1/2, rounding's) is 1/2 exactly, so that
/// `w > 0.5` is the rule's label (`exact_contains`, `contains`) everywhere.
inline double shownWinding(double w) {
    const double tie = 0.5;
    return std::abs(w - tie) <= vds::kGeneralizedWindingTie ? tie : w;
}

/// The Python Sprite: a vds::Sprite and the key of its GPU copy in
/// GlState::resident (0: none yet). The copy is owned by the GL thread's
/// state, so `_release_gl` frees it with the context; a sprite freed later
/// finds the thread stopped and calls no GL.
struct PySprite : vds::Sprite {
    explicit PySprite(vds::Sprite&& sprite) : vds::Sprite(std::move(sprite)) {}
    PySprite(const PySprite&) = delete;
    PySprite& operator=(const PySprite&) = delete;
    ~PySprite() {
        if (const std::uint64_t id = gpuId.load())
            glThread().post([id](GlState& s) { s.resident.erase(id); });
    }

    /// Set on the GL thread while the caller waits; read when the sprite is freed.
    std::atomic<std::uint64_t> gpuId{0};
};

std::shared_ptr<PySprite> wrap(vds::Sprite&& sprite);
std::shared_ptr<PySprite> spriteFromBytes(const py::bytes& data, const std::string& name);

/// The vds.Grid `grid` is, else `DTypeError` (a vds.Error and a TypeError)
/// naming what was given: pybind's own TypeError would not be a vds.Error.
vds::Grid gridFrom(const py::object& grid);

/// A mesh kept to rebuild what was made from it (pickling): its positions
/// as float32 and its triangles.
struct MeshCopy {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    explicit MeshCopy(vds::MeshView view)
        : positions(view.positions, view.positions + view.positionCount),
          triangles(view.triangles, view.triangles + view.triangleCount) {}
    /// (V float32 (n, 3), F uint32 (m, 3)): arrays the constructors read.
    py::tuple arrays() const;
};

void registerExceptions(py::module_& m);
void bindGrid(py::module_& m);
void bindMeshFunctions(py::module_& m);
void bindSprite(py::module_& m);
void bindClassifiers(py::module_& m);

} // namespace vds::python
