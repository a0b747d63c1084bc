// Wavefront OBJ, the polygonal subset: `v` and `f` statements (Wavefront
// Technologies, "Object Files (.obj)", Advanced Visualizer manual, appendix
// B1). Vertex references are v, v/vt, v//vn or v/vt/vn, 1-based, negative
// ones relative to the vertices read so far. A `\` at the end of a line
// continues the statement on the next line. Texture coordinates, normals,
// groups, materials, lines and points carry no surface and are skipped, as
// are numbers after a vertex's x y z (w, or colours, NaN or not); faces of
// fewer than 3 vertices are skipped and counted. Free-form geometry (cstype,
// surf, ...) is refused rather than dropped.
//
// The text is read in one pass with a pointer, token by token, without
// splitting it into lines first: loading is mostly this loop and the number
// conversions (std::from_chars), so it runs near their speed.
#include <vds/detail/mesh_readers.h>

#include <limits>

#include <vds/detail/text_scanner.h>

namespace vds::detail {
namespace {

constexpr std::uint64_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();
constexpr std::size_t kMaxVertexNumbers = 7; // x y z, then w or r g b [a]

/// Bytes that end a token: blanks, the line break, a comment's '#', and '\\'
/// (which does only where it ends a line).
struct Delimiters {
    bool table[256] = {};
    constexpr Delimiters() {
        for (unsigned char c : {' ', '\t', '\r', '\v', '\f', '\n', '#', '\\'}) table[c] = true;
    }
    bool operator()(char c) const { return table[static_cast<unsigned char>(c)]; }
};
constexpr Delimiters kDelimiter;

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
    ObjReader(const char* data, std::size_t size, const std::string& name)
        : at_(data), end_(data + size), name_(name) {
        if (size >= 3 && std::string_view(data, 3) == "\xEF\xBB\xBF") at_ += 3; // a UTF-8 byte order mark
    }

    TriangleMesh read() {
        for (;;) {
            skipBlanks();
            if (at_ == end_) break;
            if (*at_ == '\n') {
                ++at_;
                ++line_;
                continue;
            }
            if (*at_ == '#') {
                skipComment();
                continue;
            }
            const std::string_view keyword = token();
            if (keyword == "v")
                vertex();
            else if (keyword == "f" || keyword == "fo")
                face();
            else if (isFreeForm(keyword))
                fail("free-form geometry ('" + std::string(keyword) + "') is not supported; only polygons are read");
            else if (!isKeyword(keyword))
                fail(quoted(keyword) + " is not an OBJ statement");
            else
                while (!token().empty()) {} // a statement that carries no surface
        }
        if (furthest_ > mesh_.positions.size())
            failAtLine(name_, furthestLine_,
                       "vertex " + std::to_string(furthest_) + " does not exist (the file has " +
                           std::to_string(mesh_.positions.size()) + " vertices)");
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { failAtLine(name_, line_, what); }

    /// A `\` that ends its line (LF or CRLF, or the file).
    bool continuation(const char* p) const {
        return *p == '\\' && (p + 1 == end_ || p[1] == '\n' || (p[1] == '\r' && p + 2 < end_ && p[2] == '\n'));
    }

    /// Past blanks and line continuations, to a token, a line end, a comment or the end.
    void skipBlanks() {
        while (at_ < end_) {
            if (isBlank(*at_)) {
                ++at_;
            } else if (*at_ == '\\' && continuation(at_)) {
                const std::size_t length = end_ - at_ == 1 ? 1 : at_[1] == '\r' ? 3 : 2; // at the end, before LF, before CRLF
                at_ += length;
                line_ += length > 1;
            } else {
                break;
            }
        }
    }

    /// To the end of a comment's line, which a `\` continues here too.
    void skipComment() {
        while (at_ < end_ && *at_ != '\n') {
            if (*at_ == '\\' && continuation(at_)) {
                skipBlanks();
                continue;
            }
            ++at_;
        }
    }

    /// The statement's next token; empty at its end (a line end that is no
    /// continuation, a comment, the end of the file).
    std::string_view token() {
        skipBlanks();
        const char* start = at_;
        while (at_ < end_ && (!kDelimiter(*at_) || (*at_ == '\\' && !continuation(at_)))) ++at_;
        return {start, std::size_t(at_ - start)};
    }

    void vertex() {
        std::string_view numbers[kMaxVertexNumbers];
        std::size_t n = 0;
        for (std::string_view t; !(t = token()).empty(); ++n)
            if (n < kMaxVertexNumbers) numbers[n] = t;
        if (n < 3) fail("a vertex needs 3 coordinates, this one has " + std::to_string(n));
        if (n > kMaxVertexNumbers)
            fail("a vertex has at most " + std::to_string(kMaxVertexNumbers) + " numbers, this one has " +
                 std::to_string(n));
        const float x = parseCoordinate(numbers[0], name_, line_);
        const float y = parseCoordinate(numbers[1], name_, line_);
        const float z = parseCoordinate(numbers[2], name_, line_);
        for (std::size_t k = 3; k < n; ++k) { // not a position: any number, finite or not
            double ignored = 0.0;
            if (parseNumber(numbers[k], ignored) == NumberStatus::Malformed)
                fail("vertex attribute " + numberProblem(NumberStatus::Malformed, numbers[k], "a number"));
        }
        if (mesh_.positions.size() == kMaxVertices) fail("more than 2^32 - 1 vertices");
        mesh_.positions.emplace_back(x, y, z);
    }

    void face() {
        corners_.clear();
        for (std::string_view t; !(t = token()).empty();) corners_.push_back(reference(t));
        appendFan(mesh_, corners_);
    }

    /// The 0-based vertex index of a reference "v[/vt][/vn]"; vt and vn are
    /// checked for form only, as nothing here uses them.
    std::uint32_t reference(std::string_view token) {
        // Most references are plain digits, or digits and slashes: read
        // those here, anything else (signs, errors) below.
        std::uint64_t index = 0;
        std::size_t i = 0;
        while (i < token.size() && i < 10 && token[i] >= '0' && token[i] <= '9') index = index * 10 + std::uint64_t(token[i++] - '0');
        if (i > 0 && index > 0 && index <= kMaxVertices) {
            // v/vt, v//vn, v/vt/vn (vt, vn read past): at most two slashes, digit runs short enough for any integer type.
            bool plain = true;
            for (std::size_t k = i, slashes = 0, run = 0; k < token.size() && plain; ++k) {
                run = token[k] == '/' ? 0 : run + 1;
                plain = token[k] == '/' ? ++slashes <= 2 : token[k] >= '0' && token[k] <= '9' && run <= 18;
            }
            if (plain) {
                if (index > furthest_) {
                    furthest_ = index;
                    furthestLine_ = line_;
                }
                return std::uint32_t(index - 1);
            }
        }
        return slowReference(token);
    }

    std::uint32_t slowReference(std::string_view token) {
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
            furthestLine_ = line_;
        }
        return std::uint32_t(index - 1);
    }

    const char* at_;
    const char* end_;
    const std::string& name_;
    std::size_t line_ = 1; ///< of `at_`
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
