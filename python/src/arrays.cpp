// vds._vds: numpy arrays and Python arguments as the library's plain data (arrays.h).
#include "arrays.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <type_traits>

namespace vds::python {

namespace {

std::string dtypeText(const py::dtype& type) { return py::str(py::handle(type)).cast<std::string>(); }

bool nativeOrder(const py::dtype& type) { return type.attr("isnative").cast<bool>(); }

/// `object` as an array of two dimensions (n, 3); throws for another shape.
void requireRowsOfThree(const py::array& a, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != 3)
        throw InvalidArgument(std::string(what) + " must have shape (N, 3), not " + shapeText(a));
}

} // namespace

std::string shapeText(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

// ---- points --------------------------------------------------------------

Points viewPoints(const py::object& object, const char* what) {
    Points p;
    p.source = py::array::ensure(object);
    if (!p.source) throw InvalidArgument(std::string(what) + " must be an (N, 3) array of float32 or float64");
    const py::dtype type = p.source.dtype();
    if (type.kind() != 'f' || (type.itemsize() != 4 && type.itemsize() != 8))
        throw DTypeError(std::string(what) + " must be float32 or float64, not " + dtypeText(type) +
                         " (convert with .astype(numpy.float32))");
    // The other byte order: converted to native float64 once.
    if (!nativeOrder(type)) p.source = py::array_t<double, py::array::forcecast>::ensure(p.source);
    requireRowsOfThree(p.source, what);
    p.isDouble = p.source.dtype().itemsize() == 8;
    p.data = static_cast<const char*>(p.source.data());
    p.rowStride = p.source.strides(0);
    p.columnStride = p.source.strides(1);
    p.count = std::size_t(p.source.shape(0));
    return p;
}

double Points::at(std::size_t row, int column) const {
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

void Points::prepare(bool packedNeeded, const char* what) {
    const py::ssize_t scalar = isDouble ? py::ssize_t(sizeof(double)) : py::ssize_t(sizeof(float));
    // In place: x, y, z adjacent, rows forwards and aligned (PointsView's strides are unsigned).
    bool direct = columnStride == scalar && rowStride >= 3 * scalar && rowStride % scalar == 0 &&
                  reinterpret_cast<std::uintptr_t>(data) % std::uintptr_t(scalar) == 0;
    if (packedNeeded) direct = direct && !isDouble && rowStride == py::ssize_t(sizeof(glm::vec3));
    if (!direct) packed.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
        const double x = at(k, 0), y = at(k, 1), z = at(k, 2);
        // A float64 beyond float's range would become infinite: refuse it too.
        if (!std::isfinite(float(x)) || !std::isfinite(float(y)) || !std::isfinite(float(z)))
            throw InvalidArgument(std::string(what) + "[" + std::to_string(k) + "] = (" + std::to_string(x) + ", " +
                                  std::to_string(y) + ", " + std::to_string(z) +
                                  ") is not finite (or does not fit a float32)");
        if (!direct) packed[k] = glm::vec3(float(x), float(y), float(z));
    }
    if (!direct)
        points = PointsView(packed);
    else if (isDouble)
        points = PointsView::doubles(reinterpret_cast<const double*>(data), count, std::size_t(rowStride));
    else
        points = PointsView::floats(reinterpret_cast<const float*>(data), count, std::size_t(rowStride));
}

// ---- meshes --------------------------------------------------------------

namespace {

/// C-contiguous and aligned for 4-byte elements: what a glm::vec3 / glm::uvec3 view needs.
bool viewable(const py::array& a) {
    return (a.flags() & py::array::c_style) != 0 && reinterpret_cast<std::uintptr_t>(a.data()) % 4 == 0;
}

[[noreturn]] void badIndex(py::ssize_t t, int c, long long i, std::size_t n) {
    throw InvalidMesh("F[" + std::to_string(t) + ", " + std::to_string(c) + "] = " + std::to_string(i) +
                      " is not a vertex index (V has " + std::to_string(n) + " rows)");
}

/// Checks every index of a C-contiguous (m, 3) array of T against n.
template <class T> void checkIndices(const T* f, py::ssize_t m, std::size_t n) {
    for (py::ssize_t t = 0; t < m; ++t)
        for (int c = 0; c < 3; ++c) {
            const T i = f[3 * t + c];
            bool negative = false;
            if constexpr (std::is_signed_v<T>) negative = i < 0;
            if (negative || std::uint64_t(i) >= n) badIndex(t, c, static_cast<long long>(i), n);
        }
}

} // namespace

MeshArrays meshArrays(const py::object& vertices, const py::object& faces) {
    MeshArrays m;
    // V: the points rules (floats only), then in place or copied to float32.
    Points v = viewPoints(vertices, "V");
    m.vertices = v.source;
    const std::size_t n = v.count;
    if (!v.isDouble && viewable(v.source)) {
        m.view.positions = reinterpret_cast<const glm::vec3*>(v.data);
    } else {
        m.verticesCopied = true;
        auto copy = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(v.source);
        m.positions.resize(n);
        if (n) std::memcpy(m.positions.data(), copy.data(), n * sizeof(glm::vec3));
        m.view.positions = m.positions.data();
    }
    m.view.positionCount = n;

    // F: integers only, in place when int32/uint32 and C-contiguous.
    m.faces = py::array::ensure(faces);
    if (!m.faces) throw InvalidArgument("F must be an (M, 3) integer array");
    const py::dtype type = m.faces.dtype();
    if (type.kind() != 'i' && type.kind() != 'u')
        throw DTypeError("F must be an integer array (int32, uint32, int64, ...), not " + dtypeText(type) +
                         (type.kind() == 'f' ? " (vertex indices are whole numbers: convert with .astype(numpy.int32))"
                                             : ""));
    requireRowsOfThree(m.faces, "F");
    const py::ssize_t count = m.faces.shape(0);
    if (type.itemsize() == 4 && nativeOrder(type) && viewable(m.faces)) {
        if (type.kind() == 'i')
            checkIndices(static_cast<const std::int32_t*>(m.faces.data()), count, n);
        else
            checkIndices(static_cast<const std::uint32_t*>(m.faces.data()), count, n);
        m.view.triangles = static_cast<const glm::uvec3*>(m.faces.data());
    } else {
        m.facesCopied = true;
        // Through int64 (or uint64 for unsigned 64-bit, whose values may not fit int64).
        m.triangles.resize(std::size_t(count));
        if (type.kind() == 'u' && type.itemsize() == 8) {
            auto f = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(m.faces);
            checkIndices(f.data(), count, n);
            for (py::ssize_t t = 0; t < count; ++t)
                for (int c = 0; c < 3; ++c) m.triangles[std::size_t(t)][c] = std::uint32_t(f.data()[3 * t + c]);
        } else {
            auto f = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(m.faces);
            checkIndices(f.data(), count, n);
            for (py::ssize_t t = 0; t < count; ++t)
                for (int c = 0; c < 3; ++c) m.triangles[std::size_t(t)][c] = std::uint32_t(f.data()[3 * t + c]);
        }
        m.view.triangles = m.triangles.data();
    }
    m.view.triangleCount = std::size_t(count);
    return m;
}

// ---- other arguments -------------------------------------------------------

namespace {

/// `value` as an integer in [lo, hi] (Python int or numpy integer, not bool), else `refuse()`.
template <class Refuse> long long integerIn(const py::handle& value, long long lo, long long hi, Refuse&& refuse) {
    if (py::isinstance<py::bool_>(value)) refuse();
    PyObject* index = PyNumber_Index(value.ptr());
    if (!index) {
        PyErr_Clear();
        refuse();
    }
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(index, &overflow);
    Py_DECREF(index);
    if (PyErr_Occurred()) PyErr_Clear();
    if (overflow || v < lo || v > hi) refuse();
    return v;
}

std::string reprText(const py::handle& value) {
    std::string text = py::repr(value).cast<std::string>();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

} // namespace

unsigned threadCount(const py::object& threads, const char* what) {
    // As the command line's --threads: any whole number that fits 32 bits (the work caps it).
    return unsigned(integerIn(threads, 0, 0xffffffffLL, [&] {
        throw InvalidArgument(std::string(what) + " must be a whole number 0..4294967295 (0: one per hardware "
                              "thread), not " + reprText(threads));
    }));
}

std::uint32_t countOption(const py::object& value, const char* what) {
    return std::uint32_t(integerIn(value, 0, 0xffffffffLL, [&] {
        throw InvalidArgument(std::string(what) + " must be a non-negative integer, not " + reprText(value));
    }));
}

std::string typeName(const py::handle& value) {
    return py::str(py::type::of(value).attr("__name__")).cast<std::string>();
}

std::string textOption(const py::object& value, const char* what) {
    if (!py::isinstance<py::str>(value))
        throw DTypeError(std::string(what) + " must be a str, not " + typeName(value));
    return value.cast<std::string>();
}

std::string fsPath(const py::object& path) {
    // os.fsencode: str, bytes and os.PathLike, as the bytes the file system sees.
    return py::module_::import("os").attr("fsencode")(path).cast<std::string>();
}

void requireNotDirectory(const std::string& path) {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) throw IoError(path + ": is a directory, not a file");
}

glm::vec3 vec3From(const py::object& object, const char* what) {
    auto a = py::array::ensure(object);
    if (!a || a.dtype().kind() == 'c' || a.dtype().kind() == 'O' || a.dtype().kind() == 'U')
        throw InvalidArgument(std::string(what) + " must be three numbers");
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!d || d.ndim() != 1 || d.shape(0) != 3)
        throw InvalidArgument(std::string(what) + " must be three numbers (x, y, z), not shape " + shapeText(a));
    return glm::vec3(float(d.data()[0]), float(d.data()[1]), float(d.data()[2]));
}

glm::uvec3 dimsFrom(const py::object& object) {
    const auto count = [](const py::handle& h) {
        return std::uint32_t(integerIn(h, 1, 0xffffffffLL, [&] {
            throw InvalidArgument("grid dims must be positive cell counts, not " + reprText(h));
        }));
    };
    if (py::isinstance<py::array>(object)) return dimsFrom(object.attr("tolist")());
    if (py::isinstance<py::sequence>(object) && !py::isinstance<py::str>(object)) {
        const py::sequence s = py::reinterpret_borrow<py::sequence>(object);
        if (s.size() != 3) throw InvalidArgument("grid dims must be one integer or three (nx, ny, nz)");
        return glm::uvec3(count(s[0]), count(s[1]), count(s[2]));
    }
    return glm::uvec3(count(object));
}

py::array_t<bool> gridArray(const Grid& grid) {
    return py::array_t<bool>({py::ssize_t(grid.dims.x), py::ssize_t(grid.dims.y), py::ssize_t(grid.dims.z)});
}

} // namespace vds::python
