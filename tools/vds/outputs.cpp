#include "outputs.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include <CLI/CLI.hpp>

#include <vds/error.h>
#include <vds/mesh_io.h>
#include <vds/npy.h>

namespace cli {

namespace {

// Two names of one file are one output: compared by the canonical name of
// what they name (symlinks and "./" followed; the file need not exist yet).
std::string identity(const std::string& path) {
    if (path == kStdio) return path;
    std::error_code error;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(path), error);
    return error ? path : canonical.string();
}

bool hasExtension(const std::string& path, const char* extension) {
    const std::string tail(extension);
    return path.size() > tail.size() && path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
}

const char* extensionOf(OutputFormat format) {
    switch (format) {
    case OutputFormat::Npy: return ".npy";
    case OutputFormat::Text: return ".txt";
    case OutputFormat::Csv: return ".csv";
    case OutputFormat::Vdb: return ".vdb";
    case OutputFormat::Npz: return ".npz";
    }
    return "";
}

void writeStdout(const std::string& bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
        throw vds::IoError("<stdout>: cannot write");
}

std::vector<char> readStdin() {
    std::vector<char> bytes;
    char buffer[1 << 16];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    if (std::ferror(stdin)) throw vds::IoError("<stdin>: cannot read");
    return bytes;
}

bool startsWith(const std::vector<char>& bytes, const char* magic, std::size_t size) {
    return bytes.size() >= size && std::equal(magic, magic + size, bytes.begin());
}

} // namespace

std::vector<glm::vec3> readPointsFile(const std::string& path) {
    if (path == kStdio) {
        const std::vector<char> bytes = readStdin();
        if (startsWith(bytes, "\x93NUMPY", 6)) return vds::npyPoints(vds::parseNpy(bytes.data(), bytes.size(), "<stdin>"), "<stdin>");
        const bool ply = startsWith(bytes, "ply\n", 4) || startsWith(bytes, "ply\r\n", 5);
        return vds::parsePoints(bytes.data(), bytes.size(), ply ? vds::PointFormat::Ply : vds::PointFormat::Text, "<stdin>");
    }
    if (hasExtension(path, ".npy")) return vds::npyPoints(vds::readNpy(path), path);
    return vds::loadPoints(path);
}

std::size_t Outputs::claim(const std::string& option, const std::string& path) {
    Output output;
    output.option = option;
    output.path = path;
    output.identity = identity(path);
    for (const Output& other : outputs_)
        if (other.identity == output.identity)
            throw CLI::ValidationError(option + " and " + other.option + " name the same file " +
                                       (path == kStdio ? "(standard output)" : path) +
                                       ": one would overwrite the other");
    if (path != kStdio) output.file = std::make_unique<vds::AtomicFile>(path);
    outputs_.push_back(std::move(output));
    return outputs_.size() - 1;
}

void Outputs::write(std::size_t which, const std::string& prefix, const void* data, std::size_t bytes) {
    Output& output = outputs_.at(which);
    if (!output.file) {
        output.held = prefix + std::string(static_cast<const char*>(data), bytes);
        output.written = true;
        return;
    }
    std::FILE* f = std::fopen(output.file->path().c_str(), "wb");
    if (!f) throw vds::IoError(output.path + ": cannot write");
    const bool ok = std::fwrite(prefix.data(), 1, prefix.size(), f) == prefix.size() &&
                    (bytes == 0 || std::fwrite(data, 1, bytes, f) == bytes);
    if (std::fclose(f) != 0 || !ok) throw vds::IoError(output.path + ": cannot write (disk full?)");
    output.written = true;
}

void Outputs::commit() {
    for (const Output& output : outputs_)
        if (!output.written) throw vds::IoError(output.path + ": not written");
    for (const Output& output : outputs_)
        if (!output.file) writeStdout(output.held);
    for (const Output& output : outputs_)
        if (output.file) output.file->commit();
}

OutputFormat outputFormat(const std::string& option, const std::string& path,
                          const std::vector<OutputFormat>& supported, OutputFormat stdio) {
    if (path == kStdio) return stdio;
    std::string names;
    for (const OutputFormat format : supported) {
        if (hasExtension(path, extensionOf(format))) return format;
        names += std::string(names.empty() ? "" : ", ") + extensionOf(format);
    }
    throw CLI::ValidationError(option + ": " + path + ": unsupported output format (supported: " + names +
                               ", or '-' for standard output)");
}

namespace {
void appendValue(std::string& text, double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    text += buffer;
}
void appendValue(std::string& text, std::uint32_t v) { text += std::to_string(v); }
} // namespace

template <class T> std::string textRows(const T* values, std::size_t count, std::size_t columns, OutputFormat format) {
    const char separator = format == OutputFormat::Csv ? ',' : ' ';
    std::string text;
    for (std::size_t row = 0; row < count; ++row) {
        for (std::size_t c = 0; c < columns; ++c) {
            if (c) text += separator;
            appendValue(text, values[row * columns + c]);
        }
        text += '\n';
    }
    return text;
}

template std::string textRows<double>(const double*, std::size_t, std::size_t, OutputFormat);
template std::string textRows<std::uint32_t>(const std::uint32_t*, std::size_t, std::size_t, OutputFormat);

} // namespace cli
