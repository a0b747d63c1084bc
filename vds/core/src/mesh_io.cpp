// The only place OpenMesh is used: file formats in, plain arrays out.
#include <vds/mesh_io.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <vds/error.h>

namespace vds {
namespace {

using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

void requireReadable(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw IoError(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw IoError(path + ": is a directory");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw IoError(path + ": cannot open for reading (" + std::strerror(errno) + ")");
    if (probe.peek() == std::ifstream::traits_type::eof()) throw FormatError(path + ": file is empty");
}

void silenceOpenMesh() {
    // OpenMesh reports parse problems on its own streams; ours are one-line exceptions.
    static const bool once = [] {
        omerr().disable();
        omlog().disable();
        omout().disable();
        return true;
    }();
    (void)once;
}

PolyMesh readWithOpenMesh(const std::string& path) {
    silenceOpenMesh();
    PolyMesh mesh;
    OpenMesh::IO::Options options;
    bool ok = false;
    try {
        ok = OpenMesh::IO::read_mesh(mesh, path, options);
    } catch (const std::exception& e) {
        throw FormatError(path + ": cannot parse: " + e.what());
    }
    if (!ok) throw FormatError(path + ": cannot parse as " + lowerExtension(path).substr(1) + " (malformed or truncated)");
    return mesh;
}

} // namespace

TriangleMesh loadMesh(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off")
        throw FormatError(path + ": unsupported mesh format '" + ext + "' (expected .obj, .ply, .stl or .off)");
    requireReadable(path);
    PolyMesh mesh = readWithOpenMesh(path);
    if (ext == ".obj") {
        // OpenMesh skips OBJ vertices it cannot parse (NaN, garbage) and the
        // faces using them without saying so; a mesh silently missing parts
        // must not be baked.
        std::ifstream in(path);
        std::string line;
        std::size_t declared = 0;
        while (std::getline(in, line)) {
            const std::size_t p = line.find_first_not_of(" \t");
            if (p != std::string::npos && line.compare(p, 2, "v ") == 0) ++declared;
        }
        if (declared != mesh.n_vertices())
            throw FormatError(path + ": " + std::to_string(declared - std::min<std::size_t>(declared, mesh.n_vertices())) +
                              " of " + std::to_string(declared) +
                              " vertices could not be read (non-finite or malformed coordinates)");
    }

    TriangleMesh out;
    out.name = std::filesystem::path(path).filename().string();
    out.positions.reserve(mesh.n_vertices());
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        out.positions.emplace_back(p[0], p[1], p[2]);
    }
    out.triangles.reserve(mesh.n_faces());
    std::vector<std::uint32_t> ring;
    for (auto f : mesh.faces()) {
        ring.clear();
        for (auto v : mesh.fv_range(f)) ring.push_back(std::uint32_t(v.idx()));
        for (std::size_t k = 1; k + 1 < ring.size(); ++k) out.triangles.emplace_back(ring[0], ring[k], ring[k + 1]);
    }
    return out;
}

std::vector<glm::vec3> loadPoints(const std::string& path) {
    requireReadable(path);
    std::vector<glm::vec3> points;
    if (lowerExtension(path) == ".ply") {
        PolyMesh mesh = readWithOpenMesh(path);
        points.reserve(mesh.n_vertices());
        for (auto v : mesh.vertices()) {
            const auto& p = mesh.point(v);
            if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
                throw FormatError(path + ": vertex " + std::to_string(v.idx()) + " is not finite");
            points.emplace_back(p[0], p[1], p[2]);
        }
        return points;
    }

    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find('\0') != std::string::npos) throw FormatError(path + ": not a text file of 'x y z' lines");
    const char* s = text.c_str();
    std::size_t line = 0;
    while (*s) {
        ++line;
        const char* end = std::strchr(s, '\n');
        if (!end) end = s + std::strlen(s);
        const char* c = s;
        while (c < end && (*c == ' ' || *c == '\t' || *c == '\r')) ++c;
        if (c < end && *c != '#') {
            float v[3];
            for (int k = 0; k < 3; ++k) {
                char* next = nullptr;
                errno = 0;
                v[k] = std::strtof(c, &next);
                if (next == c || next > end)
                    throw FormatError(path + ":" + std::to_string(line) + ": expected three numbers 'x y z'");
                if (!std::isfinite(v[k]))
                    throw FormatError(path + ":" + std::to_string(line) + ": coordinate is not finite");
                c = next;
            }
            while (c < end && (*c == ' ' || *c == '\t' || *c == '\r')) ++c;
            if (c != end) throw FormatError(path + ":" + std::to_string(line) + ": expected three numbers 'x y z'");
            points.emplace_back(v[0], v[1], v[2]);
        }
        s = *end ? end + 1 : end;
    }
    return points;
}

} // namespace vds
