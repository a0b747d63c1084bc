// vds: OpenVDB files (.vdb) of what vds computes, for the programs that read
// them (Houdini, Blender, Omniverse, Warp's Volume, NanoVDB by OpenVDB's own
// converter): a narrow band as a level set, occupancy as a boolean grid.
//
// Optional: this library is built whatever the machine has, and writes
// .vdb only where OpenVDB (Debian's libopenvdb-dev) was found when vds was
// built. Elsewhere `vdbAvailable()` is false and `writeVdb` throws
// `InvalidArgument` saying so, in one line.
//
// Placement: voxel (i, j, k) of a written grid is cell (i, j, k) of the vds
// grid, and its world centre (the grid's transform: a scale by the cell size
// and a translation to the first cell's centre) is the vds cell centre,
// `Grid::cellCentre`, up to float rounding.
#pragma once

#include <cstdint>
#include <string>

#include <vds/grid.h>
#include <vds/rule.h>
#include <vds/sparse_band.h>

namespace vds {

/// True when this build writes .vdb files.
bool vdbAvailable();
/// "OpenVDB 10.0.1" where available, else "no OpenVDB".
std::string vdbLibrary();
/// vds's version, as the files' metadata name it: "0.1.0".
std::string vdsVersion();

/// What a written grid is called and where it came from.
struct VdbOptions {
    std::string gridName;  ///< the grid's name; empty: "sdf" for a band, "occupancy" for labels
    std::string source;    ///< metadata "source": the mesh file, or what the caller says
};

/// Writes `band` to `path` (whole or not at all, `AtomicFile`) as one
/// `openvdb::FloatGrid` of class level set: background W (`halfWidth`),
/// each block of the band one leaf whose band cells are active voxels with
/// their distance, its other cells inactive at -W or +W by their label;
/// whole blocks inside are inactive tiles of -W (merged into larger tiles
/// where whole nodes are inside), outside is the background. Metadata:
/// "rule", "vds_version", "source", "half_width" (mesh units) and the
/// creator "vds VERSION". Throws `InvalidArgument` without OpenVDB,
/// `IoError` when the file cannot be written.
void writeVdb(const std::string& path, const SparseBand& band, const VdbOptions& options = {});

/// Writes occupancy labels (`cells`: `grid.cellCount()` bytes, 1 inside, in
/// `Grid::index` order, as `occupancy` gives them) to `path` as one
/// `openvdb::BoolGrid`: inside cells active and true; an 8^3 block wholly
/// inside is one active tile (merged into larger tiles where whole nodes
/// are), not 512 voxels. Metadata as above, with `rule`. Throws as above,
/// and `InvalidArgument` for a slab (`Grid::first` not 0).
void writeVdb(const std::string& path, const Grid& grid, const std::uint8_t* cells, Rule rule,
              const VdbOptions& options = {});

} // namespace vds
