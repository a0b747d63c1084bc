// Wavefront OBJ, the polygonal subset: `v` and `f` statements (Wavefront
// Technologies, "Object Files (.obj)", Advanced Visualizer manual, appendix
// B1). Vertex references are v, v/vt, v//vn or v/vt/vn, 1-based, negative
// ones relative to the vertices read so far. Texture coordinates, normals,
// groups, materials, lines and points carry no surface and are skipped;
// free-form geometry (cstype, surf, ...) is refused rather than dropped.
#include "mesh_readers.h"

#include <limits>

#include "text_scanner.h"

namespace vds::detail {
namespace {

constexpr std::uint64_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();

bool isKeyword(std::string_view token) {
    for (char c : token)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return !token.empty();
}

bool isFreeForm(std::string_view keyword) {
    for (const char* k : {"cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
                          "sp", "end", "con"})
        if (keyword == k) return true;
    return false;
}

class ObjReader {
public:
    ObjReader(const char* data, std::size_t size, const std::string& name) : text_(data, size), name_(name) {}

    TriangleMesh read() {
        std::string_view line;
        while (text_.nextLine(line)) {
            Tokens tokens(beforeComment(line));
            std::string_view keyword;
            if (!tokens.next(keyword)) continue;
            if (keyword == "v")
                vertex(tokens);
            else if (keyword == "f" || keyword == "fo")
                face(tokens);
            else if (isFreeForm(keyword))
                fail("free-form geometry ('" + std::string(keyword) + "') is not supported; only polygons are read");
            else if (!isKeyword(keyword))
                fail(quoted(keyword) + " is not an OBJ statement");
        }
        if (furthest_ > mesh_.positions.size())
            failAtLine(name_, furthestLine_,
                       "vertex " + std::to_string(furthest_) + " does not exist (the file has " +
                           std::to_string(mesh_.positions.size()) + " vertices)");
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { failAtLine(name_, text_.line(), what); }

    void vertex(const Tokens& tokens) {
        // x y z, then an optional w or r g b [a] (colours some exporters add).
        if (mesh_.positions.size() == kMaxVertices) fail("more than 2^32 - 1 vertices");
        mesh_.positions.push_back(readVertexLine(tokens, 7, name_, text_.line()));
    }

    void face(Tokens& tokens) {
        corners_.clear();
        std::string_view token;
        while (tokens.next(token)) corners_.push_back(reference(token));
        if (corners_.size() < 3)
            fail("a face needs at least 3 vertices, this one has " + std::to_string(corners_.size()));
        appendFan(mesh_, corners_);
    }

    /// The 0-based vertex index of a reference "v[/vt][/vn]"; vt and vn are
    /// checked for form only, as nothing here uses them.
    std::uint32_t reference(std::string_view token) {
        std::string_view parts[3];
        std::size_t count = 0;
        for (std::string_view rest = token;;) {
            if (count == 3) fail("vertex reference " + quoted(token) + " is not v, v/vt, v//vn or v/vt/vn");
            const std::size_t slash = rest.find('/');
            parts[count++] = rest.substr(0, slash);
            if (slash == std::string_view::npos) break;
            rest.remove_prefix(slash + 1);
        }
        for (std::size_t k = 1; k < count; ++k) {
            std::int64_t ignored = 0;
            if (!parts[k].empty() && parseNumber(parts[k], ignored) != NumberStatus::Ok)
                fail("vertex reference " + quoted(token) + " is not v, v/vt, v//vn or v/vt/vn");
        }
        const std::string_view v = parts[0];
        std::int64_t index = 0;
        const NumberStatus status = parseNumber(v, index);
        if (status != NumberStatus::Ok) fail("vertex reference " + numberProblem(status, v, "an integer"));
        if (index == 0) fail("vertex reference 0: OBJ counts vertices from 1");
        if (index < 0) {
            const std::uint64_t back = std::uint64_t(-(index + 1)) + 1;
            if (back > mesh_.positions.size())
                fail("vertex reference " + std::to_string(index) + " points before the first vertex (" +
                     std::to_string(mesh_.positions.size()) + " read so far)");
            return std::uint32_t(mesh_.positions.size() - back);
        }
        // Positive references may name vertices defined further down; the
        // furthest one is checked once all are read.
        if (std::uint64_t(index) > kMaxVertices) fail("vertex reference " + std::to_string(index) + " is too large");
        if (std::uint64_t(index) > furthest_) {
            furthest_ = std::uint64_t(index);
            furthestLine_ = text_.line();
        }
        return std::uint32_t(index - 1);
    }

    TextScanner text_;
    const std::string& name_;
    TriangleMesh mesh_;
    std::vector<std::uint32_t> corners_;
    std::uint64_t furthest_ = 0; ///< largest positive reference (1-based)
    std::size_t furthestLine_ = 0;
};

} // namespace

TriangleMesh readObj(const char* data, std::size_t size, const std::string& name) {
    return ObjReader(data, size, name).read();
}

} // namespace vds::detail
