// PLY, the Stanford polygon file format (Greg Turk, "The PLY Polygon File
// Format", 1994): ascii, binary_little_endian and binary_big_endian. The
// `vertex` element's x, y, z (any scalar type) become positions; the `face`
// element's `vertex_indices` (or `vertex_index`) lists, of any integer count
// and index types, become polygons (lists of fewer than 3 are skipped and
// counted). Other vertex properties, such as colours, may be NaN. Every other element and property is read
// past, by its declared type. The header's counts must fit in the bytes after
// it before anything is allocated, and the data must end where they say. An
// ascii file laid out one element per line may hold more numbers on a line
// than its element declares (onePerLine).
#include <vds/detail/mesh_readers.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include <vds/detail/text_scanner.h>

namespace vds::detail {
namespace {

enum class Scalar : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class Encoding : std::uint8_t { Ascii, LittleEndian, BigEndian };

struct ScalarName {
    const char* name;
    Scalar type;
};
constexpr ScalarName kScalarNames[] = {
    {"char", Scalar::Int8},     {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},     {"uint8", Scalar::UInt8},
    {"short", Scalar::Int16},   {"int16", Scalar::Int16},     {"ushort", Scalar::UInt16},   {"uint16", Scalar::UInt16},
    {"int", Scalar::Int32},     {"int32", Scalar::Int32},     {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
    {"float", Scalar::Float32}, {"float32", Scalar::Float32}, {"double", Scalar::Float64}, {"float64", Scalar::Float64},
};

std::size_t bytesOf(Scalar s) {
    switch (s) {
    case Scalar::Int8:
    case Scalar::UInt8: return 1;
    case Scalar::Int16:
    case Scalar::UInt16: return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
    }
    return 0;
}

bool isInteger(Scalar s) { return s != Scalar::Float32 && s != Scalar::Float64; }

const char* nameOf(Scalar s) {
    for (const ScalarName& n : kScalarNames)
        if (n.type == s) return n.name;
    return "?";
}

struct Property {
    std::string name;
    Scalar type = Scalar::Float32; ///< of the value, or of a list's items
    bool list = false;
    Scalar countType = Scalar::UInt8; ///< of a list's length
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    std::size_t line = 0; ///< of its declaration, for messages
};

constexpr std::size_t kNone = ~std::size_t(0);

// The header: its encoding, its elements and properties, and where the
// vertex positions and face indices are, checked against the file's size
// before the data is read.
class PlyHeader {
public:
    PlyHeader(TextScanner& text, const std::string& name, std::size_t size) : text_(text), name_(name), size_(size) {
        readLines();
        findVertexAndFace();
        checkDeclaredSizes();
    }

    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    std::size_t vertex = kNone, face = kNone;   ///< the elements
    std::size_t xyz[3] = {kNone, kNone, kNone}; ///< the vertex's properties
    std::size_t indices = kNone;                ///< the face's index list
    std::uint64_t vertexCount = 0;

private:
    [[noreturn]] void failHeader(const std::string& what) const { failAtLine(name_, text_.line(), what); }

    void readLines() {
        std::string_view line;
        std::string_view magic;
        if (!text_.nextLine(line) || !Tokens(line).next(magic) || magic != "ply" || Tokens(line).count() != 1)
            failAtLine(name_, 1, "not a PLY file (no 'ply' line first)");
        bool haveFormat = false;
        while (text_.nextLine(line)) {
            Tokens tokens(line);
            std::string_view keyword;
            if (!tokens.next(keyword)) failHeader("empty header line");
            if (keyword == "comment" || keyword == "obj_info") continue;
            if (keyword == "end_header") {
                if (tokens.count() != 0) failHeader("text after end_header");
                if (!haveFormat) failHeader("the header has no format line");
                return;
            }
            std::string_view a, b, c, d;
            tokens.next(a);
            tokens.next(b);
            tokens.next(c);
            tokens.next(d);
            if (keyword == "format") {
                if (haveFormat) failHeader("a second format line");
                if (a == "ascii")
                    encoding = Encoding::Ascii;
                else if (a == "binary_little_endian")
                    encoding = Encoding::LittleEndian;
                else if (a == "binary_big_endian")
                    encoding = Encoding::BigEndian;
                else
                    failHeader("unknown format " + quoted(a) + " (ascii, binary_little_endian or binary_big_endian)");
                if (b != "1.0" || !c.empty()) failHeader("expected 'format " + std::string(a) + " 1.0'");
                haveFormat = true;
            } else if (keyword == "element") {
                if (a.empty() || b.empty() || !c.empty()) failHeader("expected 'element <name> <count>'");
                std::int64_t count = 0;
                const NumberStatus status = parseNumber(b, count);
                if (status != NumberStatus::Ok) failHeader("element count " + numberProblem(status, b, "an integer"));
                if (count < 0) failHeader("element count " + quoted(b) + " is negative");
                for (const Element& e : elements)
                    if (e.name == a) failHeader("a second element " + quoted(a));
                elements.push_back({std::string(a), std::uint64_t(count), {}, text_.line()});
            } else if (keyword == "property") {
                if (elements.empty()) failHeader("a property before any element");
                Property p;
                if (a == "list") {
                    if (d.empty() || tokens.count() != 0)
                        failHeader("expected 'property list <count type> <item type> <name>'");
                    p.list = true;
                    p.countType = scalarType(b);
                    p.type = scalarType(c);
                    p.name = std::string(d);
                    if (!isInteger(p.countType)) failHeader("a list's count type must be an integer type");
                } else {
                    if (b.empty() || !c.empty()) failHeader("expected 'property <type> <name>'");
                    p.type = scalarType(a);
                    p.name = std::string(b);
                }
                for (const Property& q : elements.back().properties)
                    if (q.name == p.name) failHeader("a second property " + quoted(p.name) + " in one element");
                elements.back().properties.push_back(std::move(p));
            } else {
                failHeader(quoted(keyword) + " is not a PLY header keyword");
            }
        }
        failAtLine(name_, text_.line(), "the header has no end_header line (truncated, or not a PLY file)");
    }

    Scalar scalarType(std::string_view token) const {
        for (const ScalarName& n : kScalarNames)
            if (token == n.name) return n.type;
        failHeader(quoted(token) + " is not a PLY type");
    }

    std::size_t findProperty(const Element& e, std::string_view name) const {
        for (std::size_t k = 0; k < e.properties.size(); ++k)
            if (e.properties[k].name == name) return k;
        return kNone;
    }

    void findVertexAndFace() {
        for (std::size_t e = 0; e < elements.size(); ++e) {
            const Element& element = elements[e];
            if (element.name == "vertex") vertex = e;
            if (element.name == "face") face = e;
            if (element.name == "tristrips" && element.count > 0)
                failAtLine(name_, element.line, "triangle strips ('tristrips') are not supported");
        }
        if (vertex != kNone) {
            const Element& v = elements[vertex];
            xyz[0] = findProperty(v, "x");
            xyz[1] = findProperty(v, "y");
            xyz[2] = findProperty(v, "z");
            for (std::size_t k : xyz)
                if (v.count > 0 && (k == kNone || v.properties[k].list))
                    failAtLine(name_, v.line, "the vertex element needs scalar properties x, y and z");
            if (v.count > std::numeric_limits<std::uint32_t>::max())
                failAtLine(name_, v.line, "more than 2^32 - 1 vertices declared");
            vertexCount = v.count;
        }
        if (face != kNone) {
            const Element& f = elements[face];
            indices = findProperty(f, "vertex_indices");
            if (indices == kNone) indices = findProperty(f, "vertex_index");
            if (f.count > 0 && (indices == kNone || !f.properties[indices].list))
                failAtLine(name_, f.line, "the face element needs a list property vertex_indices");
            if (indices != kNone && !isInteger(f.properties[indices].type))
                failAtLine(name_, f.line, "vertex indices must be of an integer type");
        }
    }

    /// The fewest bytes one instance of element `e` can take; a list,
    /// even a face's index list, may be empty.
    std::uint64_t minimumBytes(std::size_t e) const {
        std::uint64_t bytes = 0;
        const auto& properties = elements[e].properties;
        for (std::size_t k = 0; k < properties.size(); ++k) {
            const Property& p = properties[k];
            if (encoding == Encoding::Ascii) // a digit and a separator per number
                bytes += 2;
            else
                bytes += p.list ? bytesOf(p.countType) : bytesOf(p.type);
        }
        return bytes;
    }

    void checkDeclaredSizes() const {
        const std::uint64_t after = size_ - text_.offset();
        std::uint64_t room = after + (encoding == Encoding::Ascii ? 1 : 0); // the last number needs no separator
        for (std::size_t e = 0; e < elements.size(); ++e) {
            const std::uint64_t each = minimumBytes(e);
            if (each == 0) continue;
            const Element& element = elements[e];
            if (element.count > room / each) {
                // What was compared: this element's least size against what is left for it.
                const std::uint64_t before = after - std::min(after, room);
                const std::string least = element.count > UINT64_MAX / each
                                              ? std::string("more than 2^64")
                                              : std::to_string(element.count * each);
                failAtLine(name_, element.line,
                           "element " + quoted(element.name) + " declares " + std::to_string(element.count) +
                               " instances of at least " + std::to_string(each) + (each == 1 ? " byte" : " bytes") +
                               " each, " + least + " bytes, more than the " + std::to_string(std::min(after, room)) +
                               " bytes the file holds for them (" + std::to_string(after) + " after the header" +
                               (before ? ", less " + std::to_string(before) + " that the elements before take at least" : "") +
                               "): truncated, or the count is wrong");
            }
            room -= element.count * each;
        }
    }

    TextScanner& text_;
    const std::string& name_;
    std::size_t size_;
};

class PlyReader {
public:
    PlyReader(const char* data, std::size_t size, const std::string& name)
        : data_(data), size_(size), text_(data, size), name_(name) {}

    TriangleMesh read() {
        mesh_.positions.reserve(header_.vertexCount);
        if (header_.face != kNone) mesh_.triangles.reserve(header_.elements[header_.face].count);
        position_ = text_.offset();
        const bool lineByLine = header_.encoding == Encoding::Ascii && onePerLine();
        for (std::size_t e = 0; e < header_.elements.size(); ++e) {
            const Element& element = header_.elements[e];
            if (element.properties.empty()) continue; // nothing to read, however many
            const std::uint64_t fast = e == header_.vertex ? fastVertices(element)
                                       : e == header_.face ? fastFaces(element)
                                                           : 0;
            for (std::uint64_t i = fast; i < element.count; ++i) {
                if (e == header_.vertex)
                    vertex(element);
                else if (e == header_.face)
                    face(element, i);
                else
                    for (const Property& p : element.properties) skip(p, element, i);
                if (lineByLine) readPastRestOfLine();
            }
        }
        if (header_.encoding == Encoding::Ascii) {
            std::string_view token;
            if (text_.nextToken(token))
                failAtLine(name_, text_.line(), "data after the last element the header declares");
        } else if (position_ != size_) {
            const std::size_t extra = size_ - position_;
            failAtByte(name_, position_,
                       std::to_string(extra) + (extra == 1 ? " byte" : " bytes") +
                           " after the last element the header declares");
        }
        return std::move(mesh_);
    }

private:
    // ------------------------------------------------------------ data

    /// One scalar of type `s`. Every PLY type fits a double exactly. Ascii
    /// floats that are not finite numbers are NaN, or refused if `strict`.
    double scalar(Scalar s, const Element& e, std::uint64_t i, bool strict = false) {
        if (header_.encoding == Encoding::Ascii) return asciiScalar(s, e, i, strict);
        const std::size_t n = bytesOf(s);
        if (size_ - position_ < n)
            failAtByte(name_, position_,
                       "file ends inside " + e.name + " " + std::to_string(i) + " of " + std::to_string(e.count));
        valueAt_ = position_;
        position_ += n;
        return decode(s, data_ + valueAt_);
    }

    /// The binary scalar of type `s` at `at`, in the file's byte order.
    double decode(Scalar s, const char* at) const {
        unsigned char b[8];
        const std::size_t n = bytesOf(s);
        std::memcpy(b, at, n);
        if (header_.encoding == Encoding::BigEndian)
            for (std::size_t k = 0; k < n / 2; ++k) std::swap(b[k], b[n - 1 - k]);
        switch (s) {
        case Scalar::Int8: return double(std::int8_t(b[0]));
        case Scalar::UInt8: return double(b[0]);
        case Scalar::Int16: return double(load<std::int16_t>(b));
        case Scalar::UInt16: return double(load<std::uint16_t>(b));
        case Scalar::Int32: return double(load<std::int32_t>(b));
        case Scalar::UInt32: return double(load<std::uint32_t>(b));
        case Scalar::Float32: return double(load<float>(b));
        case Scalar::Float64: return load<double>(b);
        }
        return 0.0;
    }

    template <class T> static T load(const unsigned char* b) {
        T v;
        std::memcpy(&v, b, sizeof v);
        return v;
    }

    double asciiScalar(Scalar s, const Element& e, std::uint64_t i, bool strict) {
        std::string_view token;
        if (!text_.nextToken(token))
            failAtLine(name_, text_.line(),
                       "file ends inside " + e.name + " " + std::to_string(i) + " of " + std::to_string(e.count));
        if (s == Scalar::Float32 || s == Scalar::Float64) {
            double v = 0.0;
            float f = 0.0f;
            const NumberStatus status = s == Scalar::Float32 ? parseNumber(token, f) : parseNumber(token, v);
            if (status == NumberStatus::Malformed || (strict && status != NumberStatus::Ok))
                failData(e.name + " " + std::to_string(i) + ": " +
                         numberProblem(status, token, s == Scalar::Float32 ? "a 32-bit float" : "a 64-bit float"));
            if (status != NumberStatus::Ok) return std::numeric_limits<double>::quiet_NaN();
            return s == Scalar::Float32 ? double(f) : v;
        }
        std::int64_t v = 0;
        const NumberStatus status = parseNumber(token, v);
        if (status != NumberStatus::Ok) failData(numberProblem(status, token, "an integer"));
        const std::int64_t lo = s == Scalar::Int8 ? -128 : s == Scalar::Int16 ? -32768 : s == Scalar::Int32 ? INT32_MIN : 0;
        const std::int64_t hi = s == Scalar::Int8    ? 127
                                : s == Scalar::UInt8  ? 255
                                : s == Scalar::Int16  ? 32767
                                : s == Scalar::UInt16 ? 65535
                                : s == Scalar::Int32  ? INT32_MAX
                                                      : std::int64_t(UINT32_MAX);
        if (v < lo || v > hi) failData(quoted(token) + " is out of range for " + nameOf(s));
        return double(v);
    }

    /// Where the last value was read: a line of ascii, a byte of binary data.
    [[noreturn]] void failData(const std::string& what) const {
        if (header_.encoding == Encoding::Ascii) failAtLine(name_, text_.line(), what);
        failAtByte(name_, valueAt_, what);
    }

    void vertex(const Element& e) {
        const std::uint64_t i = mesh_.positions.size();
        float xyz[3] = {0.0f, 0.0f, 0.0f};
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            if (p.list) {
                skip(p, e, i);
                continue;
            }
            const bool coordinate = k == header_.xyz[0] || k == header_.xyz[1] || k == header_.xyz[2];
            const double v = scalar(p.type, e, i, coordinate);
            if (!coordinate) continue;
            if (!(std::fabs(v) <= double(std::numeric_limits<float>::max()))) {
                char text[32];
                std::snprintf(text, sizeof text, "%g", v);
                failData("vertex " + std::to_string(i) + ": coordinate " + p.name + " = " + text +
                         (std::isfinite(v) ? " is out of range for a 32-bit float" : " is not finite"));
            }
            xyz[k == header_.xyz[0] ? 0 : k == header_.xyz[1] ? 1 : 2] = float(v);
        }
        mesh_.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    }

    void face(const Element& e, std::uint64_t i) {
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            if (k != header_.indices) {
                skip(p, e, i);
                continue;
            }
            const std::uint64_t n = listLength(p, e, i);
            corners_.clear();
            const bool binary = header_.encoding != Encoding::Ascii; // listLength checked that the n indices are there
            const std::size_t size = bytesOf(p.type);
            for (std::uint64_t c = 0; c < n; ++c) {
                double index;
                if (binary) {
                    valueAt_ = position_;
                    index = decode(p.type, data_ + position_);
                    position_ += size;
                } else {
                    index = scalar(p.type, e, i);
                }
                if (!(index >= 0.0 && index < double(header_.vertexCount)))
                    failData("face " + std::to_string(i) + ": vertex index " + std::to_string(std::int64_t(index)) +
                             " is out of range (" + std::to_string(header_.vertexCount) + " vertices)");
                corners_.push_back(std::uint32_t(index));
            }
            appendFan(mesh_, corners_);
        }
    }

    /// Whether an ascii file is laid out one element instance per line, as
    /// exporters write it: its first instance (of an element without lists)
    /// fills its line. Then numbers after an instance's declared properties,
    /// up to its line's end, are read past: some writers (VCG, MeshLab's
    /// library) put more on a face's line than its header declares.
    bool onePerLine() const {
        for (const Element& e : header_.elements) {
            if (e.count == 0 || e.properties.empty()) continue;
            for (const Property& p : e.properties)
                if (p.list) return false;
            TextScanner ahead = text_;
            std::string_view line;
            while (ahead.nextLine(line))
                if (Tokens(line).count() > 0) return Tokens(line).count() == e.properties.size();
            return false;
        }
        return false;
    }

    /// The rest of the line an instance ended on: numbers only, read past.
    void readPastRestOfLine() {
        const std::size_t line = text_.line();
        Tokens rest(text_.restOfLine());
        for (std::string_view token; rest.next(token);) {
            double ignored = 0.0;
            if (parseNumber(token, ignored) == NumberStatus::Malformed)
                failAtLine(name_, line, numberProblem(NumberStatus::Malformed, token, "a number"));
        }
    }

    // The layouts most binary files have, read in tight loops: vertices of
    // float properties only, faces of nothing but a uchar-counted list of int
    // or uint indices, in the host's byte order (little-endian). Each stops
    // before anything unusual (a coordinate that is not finite, an index out
    // of range, the end of the data) and says how many it read; the general
    // code reads on from there, and names the problem.

    static bool littleEndianHost() {
        const std::uint16_t one = 1;
        unsigned char first;
        std::memcpy(&first, &one, 1);
        return first == 1;
    }

    std::uint64_t fastVertices(const Element& e) {
        if (header_.encoding != Encoding::LittleEndian || !littleEndianHost()) return 0;
        for (const Property& p : e.properties)
            if (p.list || p.type != Scalar::Float32) return 0;
        const std::size_t stride = 4 * e.properties.size();
        const std::size_t at[3] = {4 * header_.xyz[0], 4 * header_.xyz[1], 4 * header_.xyz[2]};
        std::uint64_t i = 0;
        for (; i < e.count && size_ - position_ >= stride; ++i) {
            float xyz[3];
            for (int k = 0; k < 3; ++k) std::memcpy(&xyz[k], data_ + position_ + at[k], 4);
            if (!(std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]))) break;
            mesh_.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
            position_ += stride;
        }
        return i;
    }

    std::uint64_t fastFaces(const Element& e) {
        if (header_.encoding != Encoding::LittleEndian || !littleEndianHost() || e.properties.size() != 1) return 0;
        const Property& p = e.properties[0];
        if (p.countType != Scalar::UInt8 || (p.type != Scalar::Int32 && p.type != Scalar::UInt32)) return 0;
        std::uint64_t i = 0;
        for (; i < e.count && size_ - position_ >= 1; ++i) {
            const auto n = std::size_t(static_cast<unsigned char>(data_[position_]));
            if (size_ - position_ - 1 < 4 * n) break;
            const char* at = data_ + position_ + 1;
            corners_.resize(n);
            bool inRange = true;
            for (std::size_t c = 0; c < n; ++c) {
                std::memcpy(&corners_[c], at + 4 * c, 4); // int or uint: negative ones are out of range as uint
                inRange &= corners_[c] < header_.vertexCount;
            }
            if (!inRange) break;
            position_ += 1 + 4 * n;
            appendFan(mesh_, corners_);
        }
        return i;
    }

    /// A list's length, checked against the bytes left in binary files (ascii
    /// lists end at the file's end at the latest, one token per item).
    std::uint64_t listLength(const Property& p, const Element& e, std::uint64_t i) {
        const double n = scalar(p.countType, e, i);
        if (n < 0.0) failData(e.name + " " + std::to_string(i) + ": negative list length");
        const std::uint64_t length = std::uint64_t(n);
        if (header_.encoding != Encoding::Ascii && length > (size_ - position_) / bytesOf(p.type))
            failData(e.name + " " + std::to_string(i) + ": a list of " + std::to_string(length) +
                     " items runs past the end of the file");
        return length;
    }

    void skip(const Property& p, const Element& e, std::uint64_t i) {
        if (!p.list) {
            scalar(p.type, e, i);
            return;
        }
        const std::uint64_t n = listLength(p, e, i);
        if (header_.encoding != Encoding::Ascii) {
            position_ += n * bytesOf(p.type);
            return;
        }
        for (std::uint64_t k = 0; k < n; ++k) scalar(p.type, e, i);
    }

    const char* data_;
    std::size_t size_;
    TextScanner text_;
    const std::string& name_;
    PlyHeader header_{text_, name_, size_};
    std::size_t position_ = 0; ///< of binary data
    std::size_t valueAt_ = 0;  ///< where the last binary value began
    TriangleMesh mesh_;
    std::vector<std::uint32_t> corners_;
};

} // namespace

TriangleMesh readPly(const char* data, std::size_t size, const std::string& name) {
    return PlyReader(data, size, name).read();
}

} // namespace vds::detail
