// Mesh and point files in, plain arrays out: the whole file is read into
// memory, then parsed by the format's reader (mesh_readers.h).
#include <vds/mesh_io.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <new>

#include <vds/error.h>

#include <vds/detail/file_bytes.h>
#include <vds/detail/mesh_readers.h>
#include <vds/detail/text_scanner.h>

namespace vds {
namespace detail {

void appendFan(TriangleMesh& mesh, const std::vector<std::uint32_t>& corners) {
    if (corners.size() < 3) {
        ++mesh.skippedFaces; // allowed by the formats, no triangle: counted for the validation summary
        return;
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
        mesh.triangles.emplace_back(corners[0], corners[k], corners[k + 1]);
}

glm::vec3 readVertexLine(Tokens tokens, std::size_t maxNumbers, const std::string& name, std::size_t line) {
    const std::size_t n = tokens.count();
    if (n < 3) failAtLine(name, line, "a vertex needs 3 coordinates, this one has " + std::to_string(n));
    if (n > maxNumbers)
        failAtLine(name, line,
                   "a vertex has at most " + std::to_string(maxNumbers) + " numbers, this one has " + std::to_string(n));
    std::string_view token;
    float xyz[3];
    for (float& c : xyz) {
        tokens.next(token);
        c = parseCoordinate(token, name, line);
    }
    while (tokens.next(token)) { // not a position: any number, finite or not
        double extra = 0.0;
        const NumberStatus status = parseNumber(token, extra);
        if (status == NumberStatus::Malformed)
            failAtLine(name, line, "vertex attribute " + numberProblem(status, token, "a number"));
    }
    return {xyz[0], xyz[1], xyz[2]};
}

} // namespace detail

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::vector<char> readFile(const std::string& path) {
    try {
        return detail::readWholeFile(path);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(path + ": not enough memory to read the file");
    }
}

std::vector<glm::vec3> parseTextPoints(const char* data, std::size_t size, const std::string& name) {
    if (std::find(data, data + size, '\0') != data + size)
        throw FormatError(name + ": not a text file of 'x y z' lines (it holds NUL bytes)");
    std::vector<glm::vec3> points;
    detail::TextScanner text(data, size);
    std::string_view line;
    while (text.nextLine(line)) {
        detail::Tokens tokens(line);
        std::string_view first;
        if (!tokens.next(first) || first[0] == '#') continue;
        if (tokens.count() != 2) detail::failAtLine(name, text.line(), "expected three numbers 'x y z'");
        std::string_view y, z;
        tokens.next(y);
        tokens.next(z);
        points.emplace_back(detail::parseCoordinate(first, name, text.line()),
                            detail::parseCoordinate(y, name, text.line()),
                            detail::parseCoordinate(z, name, text.line()));
    }
    return points;
}

} // namespace

MeshFormat meshFormatOf(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".obj") return MeshFormat::Obj;
    if (ext == ".ply") return MeshFormat::Ply;
    if (ext == ".stl") return MeshFormat::Stl;
    if (ext == ".off") return MeshFormat::Off;
    throw FormatError(path + ": unsupported mesh format '" + ext + "' (expected .obj, .ply, .stl or .off)");
}

TriangleMesh parseMesh(const char* data, std::size_t size, MeshFormat format, const std::string& name) {
    if (size == 0) throw FormatError(name + ": file is empty");
    try {
        TriangleMesh mesh;
        switch (format) {
        case MeshFormat::Obj: mesh = detail::readObj(data, size, name); break;
        case MeshFormat::Ply: mesh = detail::readPly(data, size, name); break;
        case MeshFormat::Stl: mesh = detail::readStl(data, size, name); break;
        case MeshFormat::Off: mesh = detail::readOff(data, size, name); break;
        }
        mesh.name = name;
        return mesh;
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(name + ": not enough memory to hold the mesh");
    }
}

TriangleMesh loadMesh(const std::string& path) {
    const MeshFormat format = meshFormatOf(path);
    const std::vector<char> bytes = readFile(path);
    TriangleMesh mesh = parseMesh(bytes.data(), bytes.size(), format, path);
    mesh.name = std::filesystem::path(path).filename().string();
    return mesh;
}

std::vector<glm::vec3> parsePoints(const char* data, std::size_t size, PointFormat format, const std::string& name) {
    if (size == 0) throw FormatError(name + ": file is empty");
    try {
        if (format == PointFormat::Ply) return detail::readPly(data, size, name).positions;
        return parseTextPoints(data, size, name);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(name + ": not enough memory to hold the points");
    }
}

std::vector<glm::vec3> loadPoints(const std::string& path) {
    const PointFormat format = lowerExtension(path) == ".ply" ? PointFormat::Ply : PointFormat::Text;
    const std::vector<char> bytes = readFile(path);
    return parsePoints(bytes.data(), bytes.size(), format, path);
}

} // namespace vds
