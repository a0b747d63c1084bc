#include "npy_slabs.h"

#include <algorithm>
#include <cstring>

#include <vds/error.h>
#include <vds/npy.h>
#include <vds/vdb.h>

#include "cli.h"
#include "outputs.h"

namespace cli {

bool isNpzPath(const std::string& path) { return path.size() > 4 && path.compare(path.size() - 4, 4, ".npz") == 0; }

void addGridFileKnobs(CLI::App& command, std::size_t& cells, std::uint64_t& zip64Above) {
    cells = kSlabCells;
    zip64Above = kZip64Above;
    // Hidden: tests' knobs, not a user's.
    command.add_option("--slab-cells", cells, "cells a slab holds at most (for tests)")
        ->transform(wholeNumber(1, std::uint64_t(1) << 40))
        ->group("");
    command.add_option("--zip64-above", zip64Above, "a .npz's sizes and offsets from this on are ZIP64 (for tests)")
        ->transform(wholeNumber(0, kZip64Above))
        ->group("");
}

std::string geometrySummary(const vds::Grid& grid) {
    const glm::vec3 cell = (grid.box.hi - grid.box.lo) / glm::vec3(grid.dims);
    char text[256];
    std::snprintf(text, sizeof text, "box [%.9g, %.9g, %.9g] to [%.9g, %.9g, %.9g], cells %.9g x %.9g x %.9g",
                  grid.box.lo.x, grid.box.lo.y, grid.box.lo.z, grid.box.hi.x, grid.box.hi.y, grid.box.hi.z, cell.x,
                  cell.y, cell.z);
    return text;
}

namespace {

/// A .npy member of `descr` and `shape` holding the `bytes` at `data`.
std::string npyMember(const char* descr, const std::vector<std::uint64_t>& shape, const void* data, std::size_t bytes) {
    return vds::npyHeader(descr, shape) + std::string(static_cast<const char*>(data), bytes);
}

std::string doubles3(const double (&v)[3]) { return npyMember("<f8", {3}, v, sizeof v); }

/// A 0-d numpy string (dtype '<U'): UTF-32, little-endian, of ASCII `text`.
std::string textMember(const std::string& text) {
    std::string utf32;
    for (const char c : text) utf32 += std::string{c, '\0', '\0', '\0'};
    return npyMember(("<U" + std::to_string(std::max<std::size_t>(text.size(), 1))).c_str(), {}, utf32.data(),
                     utf32.size());
}

/// The members before "values": the geometry, then how the values were made.
void addInfo(NpzWriter& npz, const GridFileInfo& info) {
    const vds::Grid& g = info.grid;
    double lo[3], hi[3], spacing[3];
    std::int64_t dims[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = g.box.lo[a];
        hi[a] = g.box.hi[a];
        dims[a] = g.dims[a];
        spacing[a] = (hi[a] - lo[a]) / double(g.dims[a]); // as vds.Grid.spacing
    }
    npz.add("lo.npy", doubles3(lo));
    npz.add("hi.npy", doubles3(hi));
    npz.add("dims.npy", npyMember("<i8", {3}, dims, sizeof dims));
    npz.add("spacing.npy", doubles3(spacing));
    npz.add("kind.npy", textMember(info.kind));
    npz.add("rule.npy", textMember(vds::toString(info.rule)));
    if (std::strcmp(info.kind, "band") == 0) npz.add("band.npy", npyMember("<f8", {}, &info.band, sizeof info.band));
    if (std::strcmp(info.kind, "occupancy") == 0) {
        const std::uint8_t packed = info.packed;
        npz.add("packed.npy", npyMember("|b1", {}, &packed, 1));
    }
    npz.add("version.npy", textMember(vds::vdsVersion()));
}

} // namespace

std::uint32_t slabLayers(const vds::Grid& grid, std::size_t cells, std::uint32_t steps) {
    const std::size_t layer = std::size_t(grid.dims.y) * grid.dims.z;
    const std::size_t byCells = std::max<std::size_t>(1, cells / std::max<std::size_t>(layer, 1));
    const std::size_t bySteps = std::max<std::size_t>(1, (grid.dims.x + steps - 1) / steps);
    return std::uint32_t(std::min<std::size_t>({byCells, bySteps, grid.dims.x}));
}

GridSlabWriter::GridSlabWriter(const std::string& path, const std::string& descr,
                               const std::vector<std::uint64_t>& shape, std::size_t itemBytes, const GridFileInfo& info)
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
    if (isNpzPath(path)) {
        npz_ = std::make_unique<NpzWriter>(stream_, path, info.zip64Above);
        addInfo(*npz_, info);
        npz_->begin("values.npy", header.size() + expected_);
        npz_->append(header.data(), header.size());
    } else if (std::fwrite(header.data(), 1, header.size(), stream_) != header.size()) {
        throw vds::IoError(path + ": cannot write (disk full?)");
    }
}

GridSlabWriter::~GridSlabWriter() {
    if (file_ && stream_) std::fclose(stream_); // not committed: the AtomicFile removes the temporary file
}

void GridSlabWriter::append(const void* data, std::size_t bytes) {
    if (npz_) npz_->append(data, bytes);
    else if (bytes != 0 && std::fwrite(data, 1, bytes, stream_) != bytes)
        throw vds::IoError((path_ == kStdio ? std::string("<stdout>") : path_) + ": cannot write (disk full?)");
    written_ += bytes;
}

void GridSlabWriter::commit() {
    if (written_ != expected_) throw vds::IoError(path_ + ": not written whole");
    if (npz_) npz_->finish();
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
