// The files one vds command writes, all or none. Each output is claimed
// before the work (its name checked against the others, its temporary file
// made beside it, so a missing directory fails in a moment, not after
// minutes), written whole to its temporary file, and only once every output
// is written are they renamed into place: a failure leaves every existing
// file as it was. "-" is standard output, written just before the renames.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <vds/atomic_file.h>

namespace cli {

/// "-": standard input or output.
constexpr const char* kStdio = "-";

/// Points from a .npy array of N x 3 float32 or float64, or what
/// vds::loadPoints reads; from stdin ("-") any of these, told apart by their
/// first bytes. Throws vds::IoError, vds::FormatError.
std::vector<glm::vec3> readPointsFile(const std::string& path);

class Outputs {
public:
    /// Claims `path`, given to `option` (for messages). Throws
    /// CLI::ValidationError when another option already names the same file
    /// (or both name "-"), vds::IoError when it cannot be written (a missing
    /// directory, a directory). Returns the output's number for `write`.
    std::size_t claim(const std::string& option, const std::string& path);
    /// Writes output `which` whole: `prefix` (a header), then `bytes` bytes at
    /// `data`, to its temporary file (or held for stdout). Throws vds::IoError.
    void write(std::size_t which, const std::string& prefix, const void* data, std::size_t bytes);
    /// Standard output, then every file renamed into place. Every claimed
    /// output must have been written. Throws vds::IoError.
    void commit();

private:
    struct Output {
        std::string option, path, identity; ///< identity: the file's canonical name, "-" for stdout
        std::unique_ptr<vds::AtomicFile> file; ///< none for stdout
        std::string held;                     ///< stdout's bytes, written at commit
        bool written = false;
    };
    std::vector<Output> outputs_;
};

/// How an output's values are written: a numpy array, text lines of values
/// separated by spaces, or by commas, an OpenVDB file (<vds/vdb.h>), or a
/// numpy .npz of a grid's values and geometry (npy_slabs.h).
enum class OutputFormat { Npy, Text, Csv, Vdb, Npz };

/// The format `path`'s extension names (.npy, .txt, .csv, .vdb, .npz) among `supported`;
/// `stdio` for "-". Throws CLI::ValidationError naming `option` and the
/// supported extensions for any other name.
OutputFormat outputFormat(const std::string& option, const std::string& path,
                          const std::vector<OutputFormat>& supported, OutputFormat stdio);

/// `count` rows of `columns` values as text lines in `format` (Text or Csv),
/// each value printed so that it reads back as itself.
template <class T> std::string textRows(const T* values, std::size_t count, std::size_t columns, OutputFormat format);

} // namespace cli
