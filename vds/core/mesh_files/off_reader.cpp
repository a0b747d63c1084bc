// OFF, Geomview's Object File Format (Geomview manual, "OFF Files"): a
// header "[ST][C][N]OFF", the counts "vertices faces edges" (on the header
// line, even right after the keyword as in "OFF8 6 12", or on the next), one
// vertex per line (x y z, then the normal, colour or texture coordinates the
// prefixes announce, which may be NaN), one face per line ("n i0 ... i(n-1)",
// then an optional colour of up to 4 numbers; a face of fewer than 3
// vertices is skipped and counted). '#' starts a comment. 4OFF, nOFF and
// binary OFF are refused. Exactly the declared vertices and faces must
// follow.
#include <vds/detail/mesh_readers.h>

#include <limits>

#include <vds/detail/text_scanner.h>

namespace vds::detail {
namespace {

// The fewest bytes a vertex line ("0 0 0\n") and a face line ("0\n") take.
constexpr std::uint64_t kMinVertexBytes = 6;
constexpr std::uint64_t kMinFaceBytes = 2;
constexpr std::size_t kMaxFaceColour = 4;

class OffReader {
public:
    OffReader(const char* data, std::size_t size, const std::string& name)
        : text_(data, size), size_(size), name_(name) {}

    TriangleMesh read() {
        std::string_view line;
        if (!nextContentLine(line)) failAtLine(name_, 1, "no OFF header");
        // The keyword ends with "OFF"; what follows it on the line, if
        // anything, is the counts.
        std::size_t start = 0;
        while (start < line.size() && isBlank(line[start])) ++start;
        std::size_t stop = start;
        while (stop < line.size() && !isBlank(line[stop])) ++stop;
        const std::size_t off = line.substr(start, stop - start).find("OFF");
        const std::size_t keywordEnd =
            off != std::string_view::npos && stop > start + off + 3 && isDigit(line[start + off + 3])
                ? start + off + 3 // "OFF8 6 12"
                : stop;
        checkKeyword(line.substr(start, keywordEnd - start));
        line.remove_prefix(keywordEnd);
        if (Tokens(line).count() == 0 && !nextContentLine(line))
            fail("file ends before the vertex and face counts");
        readCounts(line);

        std::uint64_t room = size_ - text_.offset() + 1; // the last line may lack its line break
        if (vertices_ > room / kMinVertexBytes || faces_ > (room - vertices_ * kMinVertexBytes) / kMinFaceBytes)
            fail("the header declares " + std::to_string(vertices_) + " vertices and " + std::to_string(faces_) +
                 " faces, more than the " + std::to_string(size_ - text_.offset()) + " bytes after it can hold");
        mesh_.positions.reserve(vertices_);
        mesh_.triangles.reserve(faces_);

        for (std::uint64_t v = 0; v < vertices_; ++v) {
            if (!nextContentLine(line))
                fail("file ends after " + std::to_string(v) + " of " + std::to_string(vertices_) + " vertices");
            vertex(line);
        }
        for (std::uint64_t f = 0; f < faces_; ++f) {
            if (!nextContentLine(line))
                fail("file ends after " + std::to_string(f) + " of " + std::to_string(faces_) + " faces");
            face(line);
        }
        if (nextContentLine(line))
            fail("more data after the " + std::to_string(vertices_) + " vertices and " + std::to_string(faces_) +
                 " faces the header declares");
        return std::move(mesh_);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { failAtLine(name_, text_.line(), what); }

    /// The next line with something in it besides a comment.
    bool nextContentLine(std::string_view& line) {
        while (text_.nextLine(line)) {
            line = beforeComment(line);
            Tokens tokens(line);
            std::string_view token;
            if (tokens.next(token)) return true;
        }
        return false;
    }

    static bool isDigit(char c) { return c >= '0' && c <= '9'; }

    void checkKeyword(std::string_view keyword) {
        const std::size_t at = keyword.rfind("OFF");
        if (at == std::string_view::npos || at + 3 != keyword.size())
            fail("not an OFF file (the first line is not 'OFF' or a variant such as 'COFF')");
        std::string_view prefix = keyword.substr(0, at);
        for (std::string_view part : {"ST", "C", "N"})
            if (prefix.substr(0, part.size()) == part) prefix.remove_prefix(part.size());
        if (prefix == "4" || prefix == "n" || prefix == "4n")
            fail(quoted(keyword) + ": only 3-dimensional OFF is supported");
        if (!prefix.empty()) fail(quoted(keyword) + " is not an OFF header ([ST][C][N]OFF)");
    }

    void readCounts(std::string_view line) {
        Tokens tokens(line);
        std::string_view token;
        std::int64_t counts[3] = {0, 0, 0};
        std::size_t n = 0;
        while (tokens.next(token)) {
            if (token == "BINARY") fail("binary OFF is not supported");
            if (n == 3) fail("the counts line holds more than 'vertices faces edges'");
            const NumberStatus status = parseNumber(token, counts[n]);
            if (status != NumberStatus::Ok || counts[n] < 0)
                fail("count " + (status != NumberStatus::Ok ? numberProblem(status, token, "an integer")
                                                             : quoted(token) + " is negative"));
            ++n;
        }
        if (n < 2) fail("expected the counts 'vertices faces edges'");
        if (std::uint64_t(counts[0]) > std::numeric_limits<std::uint32_t>::max())
            fail("more than 2^32 - 1 vertices declared");
        vertices_ = std::uint64_t(counts[0]);
        faces_ = std::uint64_t(counts[1]);
    }

    void vertex(std::string_view line) {
        // x y z, then whatever the header's prefixes announce (normal, colour, texture coordinates).
        constexpr std::size_t kMaxNumbers = 3 + 3 + 4 + 2;
        mesh_.positions.push_back(readVertexLine(Tokens(line), kMaxNumbers, name_, text_.line()));
    }

    void face(std::string_view line) {
        Tokens tokens(line);
        std::string_view token;
        tokens.next(token);
        std::int64_t n = 0;
        const NumberStatus status = parseNumber(token, n);
        if (status != NumberStatus::Ok) fail("face size " + numberProblem(status, token, "an integer"));
        if (n < 0) fail("face size " + std::to_string(n) + " is negative");
        const std::size_t left = tokens.count();
        if (std::uint64_t(n) > left)
            fail("the face declares " + std::to_string(n) + " vertices, the line holds " + std::to_string(left) +
                 " more numbers");
        if (left - std::size_t(n) > kMaxFaceColour)
            fail("the face has " + std::to_string(left - std::size_t(n)) + " numbers after its " + std::to_string(n) +
                 " vertices (a colour has at most " + std::to_string(kMaxFaceColour) + ")");
        corners_.clear();
        for (std::int64_t k = 0; k < n; ++k) {
            tokens.next(token);
            std::int64_t index = 0;
            const NumberStatus s = parseNumber(token, index);
            if (s != NumberStatus::Ok) fail("vertex index " + numberProblem(s, token, "an integer"));
            if (index < 0 || std::uint64_t(index) >= vertices_)
                fail("vertex index " + std::to_string(index) + " is out of range (the file has " +
                     std::to_string(vertices_) + " vertices, numbered from 0)");
            corners_.push_back(std::uint32_t(index));
        }
        while (tokens.next(token)) {
            double colour = 0.0;
            const NumberStatus s = parseNumber(token, colour);
            if (s == NumberStatus::Malformed) fail("face colour " + numberProblem(s, token, "a number"));
        }
        appendFan(mesh_, corners_);
    }

    TextScanner text_;
    std::size_t size_;
    const std::string& name_;
    std::uint64_t vertices_ = 0, faces_ = 0;
    TriangleMesh mesh_;
    std::vector<std::uint32_t> corners_;
};

} // namespace

TriangleMesh readOff(const char* data, std::size_t size, const std::string& name) {
    return OffReader(data, size, name).read();
}

} // namespace vds::detail
