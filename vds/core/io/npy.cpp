// The .npy format (numpy's NEP 1): the magic "\x93NUMPY", a version, the
// header length (2 bytes little-endian in version 1.0, 4 in 2.0 and 3.0),
// then a Python dict literal with 'descr', 'fortran_order' and 'shape',
// padded with spaces and a newline so that the data starts aligned.
#include <vds/npy.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>

#include <vds/atomic_file.h>
#include <vds/error.h>

namespace vds {
namespace {

[[noreturn]] void bad(const std::string& name, const std::string& what) { throw FormatError(name + ": " + what); }

std::string trim(const std::string& s) {
    const std::size_t a = s.find_first_not_of(" \t\n");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\n") - a + 1);
}

// The text of `'key': value` in the header dict, up to the next comma or
// brace outside parentheses.
std::string field(const std::string& header, const std::string& key, const std::string& name) {
    std::size_t k = header.find("'" + key + "'");
    if (k == std::string::npos) k = header.find("\"" + key + "\"");
    if (k == std::string::npos) bad(name, "npy header has no '" + key + "'");
    const std::size_t colon = header.find(':', k);
    if (colon == std::string::npos) bad(name, "npy header is malformed");
    int depth = 0;
    std::size_t e = colon + 1;
    for (; e < header.size(); ++e) {
        const char c = header[e];
        if (c == '(') ++depth;
        else if (c == ')') --depth;
        else if (depth == 0 && (c == ',' || c == '}')) break;
        if (depth < 0) bad(name, "npy header is malformed");
    }
    if (e == header.size()) bad(name, "npy header is malformed");
    return trim(header.substr(colon + 1, e - colon - 1));
}

std::uint64_t itemSize(const std::string& descr, const std::string& name) {
    if (descr.size() < 3) bad(name, "npy dtype '" + descr + "' is not supported");
    std::uint64_t size = 0;
    for (std::size_t i = 2; i < descr.size(); ++i) {
        if (descr[i] < '0' || descr[i] > '9' || size > 1024) bad(name, "npy dtype '" + descr + "' is not supported");
        size = size * 10 + std::uint64_t(descr[i] - '0');
    }
    if (size == 0) bad(name, "npy dtype '" + descr + "' is not supported");
    return size;
}

double scalar(const char* p, char order, std::uint64_t size) {
    char b[8];
    std::memcpy(b, p, size);
    if (order == '>') std::reverse(b, b + size);
    if (size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
    }
    double d;
    std::memcpy(&d, b, 8);
    return d;
}

// Bytes in memory as a stream, without a copy, so one parser reads files and memory.
class MemoryBuffer : public std::streambuf {
public:
    MemoryBuffer(const char* data, std::size_t size) {
        char* p = const_cast<char*>(data); // only read: std::streambuf wants char*
        setg(p, p, p + size);
    }
};

// A whole .npy array from `in`, which holds `fileSize` bytes from its start.
NpyArray parseNpy(std::istream& in, std::uint64_t fileSize, const std::string& path) {
    char preamble[12] = {};
    if (fileSize < 10 || !in.read(preamble, 10)) bad(path, "too short to be a .npy file");
    if (std::memcmp(preamble, "\x93NUMPY", 6) != 0) bad(path, "not a .npy file (bad magic)");
    const int major = static_cast<unsigned char>(preamble[6]);
    std::uint64_t headerLength = 0, headerStart = 10;
    if (major == 1) {
        headerLength = std::uint64_t(static_cast<unsigned char>(preamble[8])) |
                       std::uint64_t(static_cast<unsigned char>(preamble[9])) << 8;
    } else if (major == 2 || major == 3) {
        if (!in.read(preamble + 10, 2)) bad(path, "truncated .npy header");
        for (int i = 0; i < 4; ++i) headerLength |= std::uint64_t(static_cast<unsigned char>(preamble[8 + i])) << (8 * i);
        headerStart = 12;
    } else {
        bad(path, "unsupported .npy version " + std::to_string(major));
    }
    if (headerLength > fileSize - headerStart) bad(path, "truncated .npy header");
    std::string header(std::size_t(headerLength), '\0');
    if (!in.read(header.data(), std::streamsize(headerLength))) bad(path, "truncated .npy header");

    NpyArray array;
    const std::string descr = field(header, "descr", path);
    if (descr.size() < 2 || (descr.front() != '\'' && descr.front() != '"') || descr.back() != descr.front())
        bad(path, "npy dtype is not a simple type");
    array.descr = descr.substr(1, descr.size() - 2);
    const std::string fortran = field(header, "fortran_order", path);
    if (fortran != "False" && fortran != "True") bad(path, "npy fortran_order is malformed");
    array.fortranOrder = fortran == "True";
    std::string shape = field(header, "shape", path);
    if (shape.size() < 2 || shape.front() != '(' || shape.back() != ')') bad(path, "npy shape is malformed");
    shape = shape.substr(1, shape.size() - 2);
    std::uint64_t count = 1;
    std::size_t p = 0;
    while (p < shape.size()) {
        std::size_t comma = shape.find(',', p);
        if (comma == std::string::npos) comma = shape.size();
        const std::string item = trim(shape.substr(p, comma - p));
        p = comma + 1;
        if (item.empty()) continue;
        std::uint64_t value = 0;
        for (char c : item) {
            if (c < '0' || c > '9' || value > (std::numeric_limits<std::uint64_t>::max() - 9) / 10)
                bad(path, "npy shape is malformed");
            value = value * 10 + std::uint64_t(c - '0');
        }
        array.shape.push_back(value);
        if (value != 0 && count > std::numeric_limits<std::uint64_t>::max() / value) bad(path, "npy shape is too large");
        count *= value;
    }
    const std::uint64_t item = itemSize(array.descr, path);
    if (count > std::numeric_limits<std::uint64_t>::max() / item) bad(path, "npy shape is too large");
    const std::uint64_t bytes = count * item, dataStart = headerStart + headerLength;
    if (fileSize - dataStart != bytes)
        bad(path, "npy data holds " + std::to_string(fileSize - dataStart) + " bytes, its shape needs " +
                      std::to_string(bytes));
    try {
        array.data.resize(std::size_t(bytes));
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(path + ": not enough memory for " + std::to_string(bytes) + " bytes");
    }
    if (bytes && !in.read(array.data.data(), std::streamsize(bytes))) throw IoError(path + ": cannot read");
    return array;
}

} // namespace

NpyArray readNpy(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw IoError(path + ": cannot read: is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path + ": cannot open: " + std::error_code(errno, std::generic_category()).message());
    in.seekg(0, std::ios::end);
    const std::streamoff length = in.tellg();
    if (length < 0) throw IoError(path + ": cannot read (is it a directory?)");
    in.seekg(0);
    return parseNpy(in, std::uint64_t(length), path);
}

NpyArray parseNpy(const char* data, std::size_t size, const std::string& name) {
    MemoryBuffer buffer(data, size);
    std::istream in(&buffer);
    return parseNpy(in, size, name);
}

std::vector<glm::vec3> npyPoints(const NpyArray& array, const std::string& name) {
    if (array.shape.size() != 2 || array.shape[1] != 3)
        bad(name, "points must be an N x 3 array");
    const std::string& d = array.descr;
    const bool known = (d == "<f4" || d == ">f4" || d == "=f4" || d == "<f8" || d == ">f8" || d == "=f8");
    if (!known) bad(name, "points must be float32 or float64, not '" + d + "'");
    const std::uint64_t size = itemSize(d, name);
    const char order = d[0] == '=' ? '<' : d[0];
    std::vector<glm::vec3> points(std::size_t(array.shape[0]));
    for (std::size_t n = 0; n < points.size(); ++n)
        for (int c = 0; c < 3; ++c) {
            // C order: row by row; Fortran order (numpy's .T, np.asfortranarray): all x, all y, all z.
            const std::size_t at = array.fortranOrder ? std::size_t(c) * points.size() + n : n * 3 + std::size_t(c);
            const double v = scalar(array.data.data() + at * size, order, size);
            if (!std::isfinite(v) || std::fabs(v) > std::numeric_limits<float>::max())
                bad(name, "row " + std::to_string(n) + " has a non-finite coordinate");
            points[n][c] = float(v);
        }
    return points;
}

std::string npyHeader(const std::string& descr, const std::vector<std::uint64_t>& shape) {
    std::string dims; // "(3,)" for one dimension, "(2, 3)" for two
    for (std::size_t i = 0; i < shape.size(); ++i) dims += std::to_string(shape[i]) + (i + 1 < shape.size() ? ", " : "");
    if (shape.size() == 1) dims += ",";
    std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
    // Pad so that the data starts at a multiple of 64 bytes (version 1.0: 10-byte preamble).
    const std::size_t total = 10 + header.size() + 1;
    header.append((64 - total % 64) % 64, ' ');
    header += '\n';
    if (header.size() > 65535) throw InvalidArgument("npy header too long: " + std::to_string(shape.size()) + " dimensions");
    std::string preamble("\x93NUMPY\x01\x00", 8);
    preamble += char(header.size() & 0xff);
    preamble += char(header.size() >> 8);
    return preamble + header;
}

void writeNpy(const std::string& path, const std::string& descr, const std::vector<std::uint64_t>& shape,
              const void* data, std::size_t bytes) {
    const std::string header = npyHeader(descr, shape);
    AtomicFile file(path);
    std::ofstream out(file.path(), std::ios::binary | std::ios::trunc);
    out.write(header.data(), std::streamsize(header.size()));
    if (bytes) out.write(static_cast<const char*>(data), std::streamsize(bytes));
    out.close();
    if (!out) throw IoError(path + ": cannot write: " + std::error_code(errno, std::generic_category()).message());
    file.commit();
}

} // namespace vds
