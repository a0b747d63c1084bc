// A grid command's .npy output written slab by slab, so that `vds voxelize`
// and `vds sdf` hold one slab of cells at a time, never the whole grid: the
// header first, then slabs of whole x layers in order (an x layer is
// contiguous in the C-order array), all into the output's temporary file,
// renamed into place once the last byte is there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vds/atomic_file.h>
#include <vds/grid.h>

namespace cli {

/// The cells a slab holds at most unless --slab-cells says otherwise: 2^26,
/// 64 MB of labels or 256 MB of distances, whatever the grid's size.
constexpr std::size_t kSlabCells = std::size_t(1) << 26;

/// Adds the hidden option --slab-cells (the slab's size in cells, for tests
/// that force a small grid into many slabs).
void addSlabCells(CLI::App& command, std::size_t& cells);

/// The x layers of `grid` in one slab: as many as `cells` holds (at least
/// one), and no more than a `steps`-th of the grid, so that progress shows.
std::uint32_t slabLayers(const vds::Grid& grid, std::size_t cells, std::uint32_t steps);

class NpySlabWriter {
public:
    /// Claims `path` ("-": standard output, streamed) and writes the header
    /// of a C-order array of `descr` (numpy's dtype string) and `shape`;
    /// `itemBytes` the size of one element. Throws vds::IoError when the
    /// file cannot be made (a missing directory), before any work.
    NpySlabWriter(const std::string& path, const std::string& descr, const std::vector<std::uint64_t>& shape,
                  std::size_t itemBytes);
    ~NpySlabWriter();
    NpySlabWriter(const NpySlabWriter&) = delete;
    NpySlabWriter& operator=(const NpySlabWriter&) = delete;

    /// Appends the next `bytes` bytes of the array. Throws vds::IoError.
    void append(const void* data, std::size_t bytes);
    /// Renames the file into place once every byte of the array is written
    /// (vds::IoError otherwise); without it, the destructor removes it.
    void commit();

private:
    std::string path_;
    std::unique_ptr<vds::AtomicFile> file_; ///< none for standard output
    std::FILE* stream_ = nullptr;
    std::uint64_t expected_ = 0, written_ = 0;
};

/// "labelled N of M x layers" lines while a slab loop runs past a second,
/// at most one a second.
class SlabProgress {
public:
    SlabProgress(std::function<void(const std::string&)> print, const char* verb, std::uint32_t layers);
    void done(std::uint32_t layers);

private:
    std::function<void(const std::string&)> print_;
    const char* verb_;
    std::uint32_t total_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    double printed_ = 0.0;
};

} // namespace cli
