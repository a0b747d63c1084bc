#include "npy_slabs.h"

#include <algorithm>

#include <vds/error.h>
#include <vds/npy.h>

#include "cli.h"
#include "outputs.h"

namespace cli {

void addSlabCells(CLI::App& command, std::size_t& cells) {
    cells = kSlabCells;
    command.add_option("--slab-cells", cells, "cells a slab holds at most (for tests)")
        ->transform(wholeNumber(1, std::uint64_t(1) << 40))
        ->group(""); // hidden: a test's knob, not a user's
}

std::uint32_t slabLayers(const vds::Grid& grid, std::size_t cells, std::uint32_t steps) {
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const std::size_t byCells = std::max<std::size_t>(1, cells / std::max<std::size_t>(layer, 1));
    const std::size_t bySteps = std::max<std::size_t>(1, (grid.dims.x + steps - 1) / steps);
    return std::uint32_t(std::min<std::size_t>({byCells, bySteps, grid.dims.x}));
}

NpySlabWriter::NpySlabWriter(const std::string& path, const std::string& descr,
                             const std::vector<std::uint64_t>& shape, std::size_t itemBytes)
    : path_(path) {
    expected_ = itemBytes;
    for (std::uint64_t n : shape) expected_ *= n;
    const std::string header = vds::npyHeader(descr, shape);
    if (path == kStdio) {
        stream_ = stdout;
    } else {
        file_ = std::make_unique<vds::AtomicFile>(path);
        stream_ = std::fopen(file_->path().c_str(), "wb");
        if (!stream_) throw vds::IoError(path + ": cannot write");
    }
    if (std::fwrite(header.data(), 1, header.size(), stream_) != header.size())
        throw vds::IoError(path + ": cannot write (disk full?)");
}

NpySlabWriter::~NpySlabWriter() {
    if (file_ && stream_) std::fclose(stream_); // not committed: the AtomicFile removes the temporary file
}

void NpySlabWriter::append(const void* data, std::size_t bytes) {
    if (bytes != 0 && std::fwrite(data, 1, bytes, stream_) != bytes)
        throw vds::IoError((path_ == kStdio ? std::string("<stdout>") : path_) + ": cannot write (disk full?)");
    written_ += bytes;
}

void NpySlabWriter::commit() {
    if (written_ != expected_) throw vds::IoError(path_ + ": not written whole");
    const bool ok = std::fflush(stream_) == 0;
    if (file_) {
        const bool closed = std::fclose(stream_) == 0;
        stream_ = nullptr;
        if (!ok || !closed) throw vds::IoError(path_ + ": cannot write (disk full?)");
        file_->commit();
    } else if (!ok) {
        throw vds::IoError("<stdout>: cannot write");
    }
}

SlabProgress::SlabProgress(std::function<void(const std::string&)> print, const char* verb, std::uint32_t layers)
    : print_(std::move(print)), verb_(verb), total_(layers) {}

void SlabProgress::done(std::uint32_t layers) {
    constexpr double kEvery = 1.0; // seconds between lines
    const double seconds = secondsSince(start_);
    if (seconds - printed_ < kEvery) return;
    printed_ = seconds;
    reportSteps(print_, verb_, layers, total_, "x layers", seconds);
}

} // namespace cli
