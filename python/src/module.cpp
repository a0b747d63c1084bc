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
#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include <pthread.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <glm/mat4x4.hpp>

#include <vds/all.h>
#include <vds/detail/aligned_axes.h>
#include <vds/error.h>
#include <vds/vds_file.h>

#include "arrays.h"
#include "distance.h"

namespace py = pybind11;
using vds::python::DTypeError;
using vds::python::MeshArrays;
using vds::python::Points;

namespace {

using BoolArray = py::array_t<bool, py::array::c_style>;

// ---- warnings --------------------------------------------------------------

/// vds.MeshWarning, set by the module's init.
PyObject* meshWarning = nullptr;

/// What the library says about a usable mesh and `rule`: the message of
/// `requireInsideDefined` where inside is not defined by the rule (open
/// meshes, orientation conflicts for the winding rule), else
/// `insideWarning`'s; empty when there is nothing to say. The CLI's texts.
std::string insideMessage(const vds::MeshReport& report, const std::string& name, vds::Rule rule) {
    try {
        vds::requireInsideDefined(report, name, rule);
    } catch (const vds::InvalidMesh& e) {
        return e.what();
    }
    return vds::insideWarning(report, rule);
}

/// warnings.warn(message, vds.MeshWarning) from the caller's line; needs the GIL.
void warn(const std::string& message) {
    if (message.empty()) return;
    if (PyErr_WarnEx(meshWarning, message.c_str(), 1) < 0) throw py::error_already_set();
}

/// The warning of a sprite baked from a mesh that bounds no solid, asked by
/// a rule that answers for solids (the CLI's).
void warnOpenSprite(const vds::Sprite& sprite, vds::Rule rule) {
    if (sprite.status == vds::SolidStatus::Open && rule != vds::Rule::GeneralizedWinding)
        warn(vds::openSpriteMessage(sprite.validation, rule));
}

// ---- options ---------------------------------------------------------------

vds::ClassifyOptions classifyOptions(const std::string& rule, const py::object& threads) {
    vds::ClassifyOptions options;
    options.rule = vds::parseRule(rule);
    options.threads = vds::python::threadCount(threads);
    return options;
}

py::dict statsDict(const vds::ClassifyStats& stats) {
    py::dict d;
    d["certain"] = stats.certain;
    d["exact"] = stats.exact;
    return d;
}

// ---- GL ----------------------------------------------------------------------

/// The module's GL objects: its context, GPU classifier and sweep, made on
/// first use, the sprites resident on it and the GPU classifiers made on it.
/// Touched only on the GL thread (`GlThread`), where the context stays
/// current: GL objects belong to the thread and context they were made on.
struct GlState {
    std::unique_ptr<vds::GlContext> gl;
    std::unique_ptr<vds::GpuClassifier> classifier;
    std::unique_ptr<vds::GpuOccupancy> occupancy;
    /// GPU copies of Python sprites (`PySprite::gpuId`), kept between
    /// gpu=True calls; released with the context.
    std::unordered_map<std::uint64_t, std::unique_ptr<vds::GpuSprite>> resident;
    /// Classifiers of GPU methods (`PyClassifier::glId`); released with the context.
    std::unordered_map<std::uint64_t, std::unique_ptr<vds::Classifier>> classifiers;

    /// The context, made if need be (and current on the GL thread from then on).
    const vds::GlContext& context() {
        if (!gl) gl = std::make_unique<vds::GlContext>();
        return *gl;
    }

    /// Frees everything, the context last.
    void clear() {
        if (gl) gl->makeCurrent();
        resident.clear();
        classifiers.clear();
        classifier.reset();
        occupancy.reset();
        gl.reset();
    }
};

/// Set in a child made by fork() while the parent's GL thread ran: the
/// driver's own threads (llvmpipe's rasterizer pool, say) did not come along,
/// and GL in the child would wait for them forever.
std::atomic<bool> glLostInFork{false};
constexpr const char* kLostInFork =
    "GL was in use when this process was forked from its parent, and a forked child cannot use the driver "
    "the parent started: use multiprocessing's \"spawn\" start method, or call vds._release_gl() before forking";

/// Keys of resident sprites and GPU classifiers, never reused: not across
/// restarts of the GL thread, nor in a forked child (whose sprites may hold
/// their parent's keys).
std::atomic<std::uint64_t> nextGlId{1};

/// One thread that runs every GL call of the module, one task at a time, in
/// the order given: Python threads hand it their GL work and wait (without
/// the GIL), and frees are queued without waiting, so a Python object may be
/// freed on any thread at any time. Started by the first GL task, stopped by
/// `_release_gl` (atexit), which frees the GL objects and the context on
/// this thread; a later GL task starts it again with a new context. Made
/// once and never destroyed (no static destructor may touch GL or threads).
class GlThread {
public:
    /// Runs `task` on the GL thread and waits for it; rethrows its exception.
    /// The caller must not hold the GIL.
    void run(const std::function<void(GlState&)>& task) {
        if (glLostInFork) throw vds::GlUnavailable(kLostInFork);
        std::promise<void> done;
        std::future<void> result = done.get_future();
        {
            std::unique_lock<std::mutex> lock(mutex_);
            start(lock);
            queue_.emplace_back([&task, &done](GlState& state) {
                try {
                    task(state);
                    done.set_value();
                } catch (...) {
                    done.set_exception(std::current_exception());
                }
            });
        }
        wake_.notify_one();
        result.get();
    }

    /// Queues `task` without waiting, if the thread runs (a stopped thread
    /// took every GL object with it: nothing is left to free).
    void post(std::function<void(GlState&)> task) noexcept {
        try {
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                if (!worker_.joinable() || stopping_) return;
                queue_.emplace_back(std::move(task));
            }
            wake_.notify_one();
        } catch (...) {
            // Out of memory queueing a free: the object is freed with the context.
        }
    }

    /// Frees every GL object and the context on the GL thread and stops it.
    void stop() {
        std::thread worker;
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            if (!worker_.joinable()) return;
            stopping_ = true;
            worker.swap(worker_);
        }
        wake_.notify_one();
        worker.join();
        const std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = false;
        live_ = false;
    }

    /// True from the thread's start to the end of `stop`; read without the
    /// mutex (in a child process after fork, another thread may have held it).
    bool live() const noexcept { return live_; }

    bool running() {
        const std::lock_guard<std::mutex> lock(mutex_);
        return worker_.joinable() && !stopping_;
    }

private:
    void start(std::unique_lock<std::mutex>& lock) {
        // A stop under way: let it finish, then start afresh.
        while (stopping_) {
            lock.unlock();
            std::this_thread::yield();
            lock.lock();
        }
        if (!worker_.joinable()) {
            worker_ = std::thread([this] { loop(); });
            live_ = true;
        }
    }

    void loop() {
        GlState state;
        for (;;) {
            std::function<void(GlState&)> task;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
                if (queue_.empty()) break; // stopping, and every task done
                task = std::move(queue_.front());
                queue_.pop_front();
            }
            try {
                task(state); // run()'s tasks hand their exceptions to the caller
            } catch (...) {
                // A free that failed (a context lost): its objects go with the context.
            }
        }
        try {
            state.clear();
        } catch (...) {
            // A context that cannot be made current at exit: its objects go with the process.
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void(GlState&)>> queue_;
    std::thread worker_;
    bool stopping_ = false;
    std::atomic<bool> live_{false};
};

GlThread*& glThreadSlot() {
    static GlThread* thread = new GlThread; // leaked on purpose, see above
    return thread;
}

GlThread& glThread() { return *glThreadSlot(); }

/// In a child made by fork() the GL thread does not exist (only the forking
/// thread is copied): the child leaves the parent's objects alone (leaked)
/// and gets a GL thread of its own, which refuses GL where the parent's was
/// live (`glLostInFork`) and otherwise starts on the child's first GL call.
void forgetGlThreadInChild() {
    if (glThreadSlot()->live()) glLostInFork = true;
    glThreadSlot() = new GlThread;
}

void releaseGl() {
    py::gil_scoped_release released;
    glThread().stop();
}

// ---- sprites ---------------------------------------------------------------

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

std::shared_ptr<PySprite> wrap(vds::Sprite&& sprite) { return std::make_shared<PySprite>(std::move(sprite)); }

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

BoolArray spriteContains(PySprite& sprite, const py::object& points, const std::string& rule, bool gpu,
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

BoolArray spriteOccupancy(PySprite& sprite, const vds::Grid& grid, const std::string& rule, bool gpu,
                          const py::object& threads) {
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
    if (vds::detail::sweepsByColumns(sprite.grid)) { // the condition of GpuOccupancy's column sweep
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
    for (std::size_t k = 0; k < p.count; ++k) out[k] = sprite.generalizedWinding(p.points[k]);
    return numbers;
}

/// vds.bake: the mesh's warning (as `vds bake` prints it), then the bake.
std::shared_ptr<PySprite> bakeMesh(const py::object& vertices, const py::object& faces, const py::object& resolution,
                                   const std::string& axis, const std::string& method, const std::string& name) {
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
    warn(insideMessage(report, name, vds::Rule::Parity));
    py::gil_scoped_release released;
    if (autoAxis) options.axis = vds::chooseViewAxis(mesh.view, options.resolution).axis;
    // Auto: the CPU baker where no GL can be had; on a context, the GL layer's choice.
    if (options.method == vds::BakeMethod::Auto && !vds::glAvailable()) options.method = vds::BakeMethod::Cpu;
    if (options.method == vds::BakeMethod::Cpu) return wrap(vds::bakeCpu(mesh.view, options));
    vds::Sprite sprite;
    glThread().run([&](GlState& s) { sprite = vds::bake(s.context(), mesh.view, options); });
    return wrap(std::move(sprite));
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
BoolArray meshOccupancy(const py::object& vertices, const py::object& faces, const vds::Grid& grid,
                        const std::string& rule, const py::object& threads) {
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

class PyExact {
public:
    PyExact(const py::object& vertices, const py::object& faces, const std::string& axis) {
        const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
        const vds::Axis a = vds::parseAxis(axis);
        py::gil_scoped_release released;
        report_ = vds::validateMesh(mesh.view);
        exact_ = std::make_unique<vds::ExactClassifier>(mesh.view, a); // copies the triangles
    }
    BoolArray contains(const py::object& points, const std::string& rule, const py::object& threads) const {
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
        for (std::size_t k = 0; k < p.count; ++k) out[k] = exact_->generalizedWinding(p.points[k]);
        return numbers;
    }
    std::size_t boundaryEdges() const { return exact_->boundaryEdgeCount(); }

private:
    vds::MeshReport report_;
    std::unique_ptr<vds::ExactClassifier> exact_;
};

// ---- classifiers -----------------------------------------------------------

/// vds.Classifier: any `Method`, made by vds::makeClassifier. A CPU method's
/// classifier is owned here; a GPU method's lives in GlState::classifiers
/// (it belongs to the module's context) under `glId`.
class PyClassifier {
public:
    /// From a mesh.
    PyClassifier(const py::object& vertices, const py::object& faces, const std::string& methodName,
                 const py::object& resolution, const std::string& axis, const std::string& bakeMethod,
                 const py::object& slices, const py::object& threads, const std::string& name)
        : method_(vds::parseEnum<vds::Method>(methodName)) {
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
        : method_(vds::parseEnum<vds::Method>(methodName)) {
        spriteOpen_ = sprite.status == vds::SolidStatus::Open;
        spriteValidation_ = sprite.validation;
        py::gil_scoped_release released;
        vds::Sprite copy = static_cast<const vds::Sprite&>(sprite);
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

    py::object classify(const py::object& points, const std::string& rule, const py::object& threads,
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

    BoolArray occupancy(const vds::Grid& grid, const std::string& rule, const py::object& threads) const {
        const vds::ClassifyOptions options = classifyOptions(rule, threads);
        vds::requireRule(method_, options.rule);
        warnFor(options.rule);
        BoolArray cells = vds::python::gridArray(grid);
        auto* out = reinterpret_cast<std::uint8_t*>(cells.mutable_data());
        py::gil_scoped_release released;
        run([&](const vds::Classifier& c) { c.occupancy(grid, out, options); });
        return cells;
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
            warn(vds::openSpriteMessage(spriteValidation_, rule));
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
};

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

// ---- grids -----------------------------------------------------------------

vds::Grid makeGrid(const py::object& lo, const py::object& hi, const py::object& dims) {
    vds::Grid grid;
    grid.box.lo = vds::python::vec3From(lo, "lo");
    grid.box.hi = vds::python::vec3From(hi, "hi");
    grid.dims = vds::python::dimsFrom(dims);
    vds::checkGrid(grid);
    return grid;
}

py::tuple tuple3(const glm::vec3& v) { return py::make_tuple(double(v.x), double(v.y), double(v.z)); }

py::array_t<float> cellCentres(const vds::Grid& grid) {
    py::array_t<float> c({py::ssize_t(grid.dims.x), py::ssize_t(grid.dims.y), py::ssize_t(grid.dims.z), py::ssize_t(3)});
    auto* out = reinterpret_cast<glm::vec3*>(c.mutable_data());
    py::gil_scoped_release released;
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k) out[grid.index(i, j, k)] = grid.cellCentre(i, j, k);
    return c;
}

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

const char* const kRuleDoc = R"doc(
rule: "parity" (odd crossings in front), "winding" (non-zero winding) or
    "generalized-winding" (the generalized winding number above 1/2: defined
    for open meshes and soups too). A mesh that bounds no solid by the rule
    asked gets a vds.MeshWarning, with the command-line tool's text.)doc";

} // namespace

PYBIND11_MODULE(_vds, m) {
    m.doc() = "vds: point-in-solid tests with volumetric depth sprites (the compiled part; use `import vds`)";
    registerExceptions(m);
    vds::python::registerDistance(m);
    pthread_atfork(nullptr, nullptr, &forgetGlThreadInChild);

    py::class_<vds::Grid>(m, "Grid", R"doc(
A regular grid of cells over a box, the one grid of every occupancy call:
Grid(lo, hi, dims), lo and hi the box's corners (x, y, z; stored as float32,
as the C++ vds::Grid), dims one cell count for all three axes or (nx, ny, nz).

Cell (i, j, k) has the centre lo + (i + 1/2, j + 1/2, k + 1/2) * (hi - lo) / dims,
evaluated in float64 and rounded to float32 (`cell_centres`). Occupancy
arrays have the shape (nx, ny, nz), C order, indexed [i, j, k] (x slowest,
z fastest), as the C++ `Grid::index`. Raises vds.InvalidArgument for a zero
dimension, more than 2^34 cells, or a box that is empty or not finite.)doc")
        .def(py::init(&makeGrid), py::arg("lo"), py::arg("hi"), py::arg("dims"))
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
        .def_property_readonly("cell_count", &vds::Grid::cellCount)
        .def("cell_centres", &cellCentres,
             "(nx, ny, nz, 3) float32: every cell's centre, as the library computes it (see the class doc).")
        .def("__repr__", [](const vds::Grid& g) {
            const auto t = [](const glm::vec3& v) { return py::repr(tuple3(v)).cast<std::string>(); };
            return "vds.Grid(lo=" + t(g.box.lo) + ", hi=" + t(g.box.hi) + ", dims=(" + std::to_string(g.dims.x) + ", " +
                   std::to_string(g.dims.y) + ", " + std::to_string(g.dims.z) + "))";
        });

    py::class_<PySprite, std::shared_ptr<PySprite>>(m, "Sprite", R"doc(
A volumetric depth sprite: a closed mesh baked into layered depth columns.

Made by `vds.bake`, `vds.read` or `vds.from_bytes`. Answers inside/outside
for points in the mesh's coordinates (after any `transform`). Classifying is
thread safe; `transform` must not run while another thread classifies.
Pickles as its .vds file bytes.)doc")
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
holes of an open one; 0 outside the sprite's box. `ExactClassifier` gives the
exact values. Raises vds.InvalidArgument for a version 1 file of an open mesh.)doc")
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
"slicemap", "slicemap-local", "solid", "solid-compute" or a voxel method's
"-gpu" form. resolution: texels (sprites, certified bands) or cells (voxel
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
        .def("contains", [](const PyClassifier& c, const py::object& points, const std::string& rule,
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
        .def("__repr__", [](const PyClassifier& c) { return "<vds.Classifier " + c.summary() + ">"; });

    py::class_<PyExact>(m, "ExactClassifier", R"doc(
The exact classifier on a mesh's triangles (exact predicates, no sprite).

V: (n, 3) float32/float64 vertex positions (kept as float32), F: (m, 3)
integer vertex indices, counter-clockwise seen from outside. The triangles
are copied; build once, ask many times (thread safe). The same labels as
Classifier(V, F, "exact").)doc")
        .def(py::init<const py::object&, const py::object&, const std::string&>(), py::arg("V"), py::arg("F"),
             py::arg("axis") = "z")
        .def("contains", &PyExact::contains, py::arg("points"), py::arg("rule") = "parity", py::arg("threads") = 0,
             (std::string("(N, 3) float points -> (N,) bool.") + kRuleDoc).c_str())
        .def("winding_numbers", &PyExact::windingNumbers, py::arg("points"),
             "(N, 3) float points -> (N,) float64 generalized winding numbers (1 inside a closed mesh, 0 outside).")
        .def_property_readonly("boundary_edges", &PyExact::boundaryEdges,
                               "edges whose uses do not cancel: 0 for a mesh that bounds a solid");

    m.def("bake", &bakeMesh, py::arg("V"), py::arg("F"), py::arg("resolution") = 1024, py::arg("axis") = "auto",
          py::arg("method") = "auto", py::arg("name") = "", R"doc(
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
Raises vds.InvalidMesh for an unusable mesh (empty, non-finite, bad
indices); an open or inconsistently oriented mesh is baked with status
"open" and a vds.MeshWarning. GL methods raise vds.GlUnavailable where no GL
context can be had. Releases the GIL.)doc");
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
"inconsistent_edges", "degenerate_triangles", ...), "closed" (the parity rule
defines inside), "oriented" (the winding rule too), "manifold", "usable",
"bounds" ((lo, hi) of the used vertices) and the one-line "summary". Indices
out of range raise vds.InvalidMesh, as everywhere.)doc");
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
    m.def("_methods", &methodTable, "The method table as dicts (vds.methods() wraps them).");
    m.def("_mesh_copies", [](const py::object& vertices, const py::object& faces) {
              const MeshArrays mesh = vds::python::meshArrays(vertices, faces);
              return py::make_tuple(mesh.verticesCopied, mesh.facesCopied);
          }, "(V copied, F copied): whether (V, F) would be copied or read in place (for tests).");
    m.def("gl_available", [] {
              if (glLostInFork) return py::make_tuple(false, kLostInFork);
              std::string reason;
              const bool ok = vds::glAvailable(&reason);
              return py::make_tuple(ok, reason);
          }, "(bool, reason): whether a headless GL context can be had here, and why not.");
    m.def("_gpu_resident", [] {
              py::gil_scoped_release released;
              std::size_t count = 0;
              if (glThread().running()) glThread().run([&](GlState& s) { count = s.resident.size(); });
              return count;
          }, "How many sprites have a GPU copy resident on the module's context (for tests).");
    m.def("_release_gl", &releaseGl, "Frees the module's GL context (registered with atexit by vds/__init__.py).");
}
