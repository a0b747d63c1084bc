// A grid command's .npy or .npz output written slab by slab, so that `vds
// voxelize` and `vds sdf` hold one slab of cells at a time, never the whole
// grid: the header first, then slabs of whole x layers in order (an x layer is
// contiguous in the C-order array), all into the output's temporary file,
// renamed into place once the last byte is there. A .npz holds the grid's
// geometry beside the values (docs/format.md, "Grid files").
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
#include <vds/rule.h>

#include "npz_writer.h"

namespace cli {

/// The cells a slab holds at most unless --slab-cells says otherwise: 2^26,
/// 64 MB of labels or 256 MB of distances, whatever the grid's size.
constexpr std::size_t kSlabCells = std::size_t(1) << 26;

/// The x layers of `grid` in one slab: as many as `cells` holds (at least
/// one), and no more than a `steps`-th of the grid, so that progress shows.
std::uint32_t slabLayers(const vds::Grid& grid, std::size_t cells, std::uint32_t steps);

/// What a .npz grid file holds beside its values: the grid (its box, cells
/// and spacing) and how the values were made.
struct GridFileInfo {
    vds::Grid grid;
    const char* kind = "occupancy"; ///< "occupancy", "sdf" (a full grid) or "band"
    vds::Rule rule = vds::Rule::Parity;
    double band = 0.0;   ///< the band's half-width, for kind "band"
    bool packed = false; ///< occupancy eight cells a byte
    std::uint64_t zip64Above = kZip64Above; ///< --zip64-above (tests)
};

/// True for a path that names the .npz form.
bool isNpzPath(const std::string& path);

/// Adds the hidden options --slab-cells (the slab's size in cells, for tests
/// that force a small grid into many slabs) and --zip64-above (the size from
/// which a .npz's fields are ZIP64, for tests that force it on a small grid).
void addGridFileKnobs(CLI::App& command, std::size_t& cells, std::uint64_t& zip64Above);

/// "box [x0, y0, z0] to [x1, y1, z1], cells 0.1 x 0.1 x 0.1": the summary
/// line's words for the geometry a .npz keeps.
std::string geometrySummary(const vds::Grid& grid);

class GridSlabWriter {
public:
    /// Claims `path` ("-": standard output, streamed) and writes the header
    /// of a C-order array of `descr` (numpy's dtype string) and `shape`;
    /// `itemBytes` the size of one element. A path ending in .npz gets the
    /// .npz form: `info` written first, then the values as its member
    /// "values". Throws vds::IoError when the file cannot be made (a missing
    /// directory), before any work. "-" is always the .npy form (a .npz's
    /// CRCs are patched in at the end: it needs a file).
    GridSlabWriter(const std::string& path, const std::string& descr, const std::vector<std::uint64_t>& shape,
                   std::size_t itemBytes, const GridFileInfo& info);
    ~GridSlabWriter();
    GridSlabWriter(const GridSlabWriter&) = delete;
    GridSlabWriter& operator=(const GridSlabWriter&) = delete;

    /// Appends the next `bytes` bytes of the array. Throws vds::IoError.
    void append(const void* data, std::size_t bytes);
    /// Renames the file into place once every byte of the array is written
    /// (vds::IoError otherwise); without it, the destructor removes it.
    void commit();

private:
    std::string path_;
    std::unique_ptr<vds::AtomicFile> file_; ///< none for standard output
    std::FILE* stream_ = nullptr;
    std::unique_ptr<NpzWriter> npz_; ///< the .npz form
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
