// vds: .vdb files with OpenVDB (<vds/vdb.h>): a sparse band's blocks become
// the level set's leaves one for one (both are 8^3 cells in the same bit
// order), whole blocks inside become tiles.
#include <vds/vdb.h>

#include <algorithm>
#include <mutex>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tree/ValueAccessor.h>

#include <vds/atomic_file.h>
#include <vds/error.h>

namespace vds {

namespace {

constexpr std::uint32_t kSide = kBandBlockSide;
/// Blocks along each axis of a node one level above the leaves' parents
/// (OpenVDB's default tree: 16^3 leaves a node, 8^3 cells a leaf).
constexpr std::uint32_t kNodeBlocks = 16;
static_assert(openvdb::FloatTree::LeafNodeType::DIM == kSide, "a band block is one OpenVDB leaf");

void initialise() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

/// Voxel (i, j, k) at world lo + (i + 1/2, j + 1/2, k + 1/2) * cell.
openvdb::math::Transform::Ptr transformOf(const Grid& grid) {
    const glm::dvec3 lo(grid.box.lo), cell = (glm::dvec3(grid.box.hi) - lo) / glm::dvec3(grid.dims);
    openvdb::math::Transform::Ptr t = openvdb::math::Transform::createLinearTransform(1.0);
    t->preScale(openvdb::Vec3d(cell.x, cell.y, cell.z));
    t->postTranslate(openvdb::Vec3d(lo.x + 0.5 * cell.x, lo.y + 0.5 * cell.y, lo.z + 0.5 * cell.z));
    return t;
}

void describe(openvdb::GridBase& out, const Grid& grid, Rule rule, const VdbOptions& options,
              const std::string& defaultName) {
    out.setName(options.gridName.empty() ? defaultName : options.gridName);
    out.setTransform(transformOf(grid));
    out.setCreator("vds " + vdsVersion());
    out.insertMeta("rule", openvdb::StringMetadata(toString(rule)));
    out.insertMeta("vds_version", openvdb::StringMetadata(vdsVersion()));
    out.insertMeta("source", openvdb::StringMetadata(options.source));
}

void writeGrid(const std::string& path, const openvdb::GridBase::Ptr& grid) {
    AtomicFile file(path);
    try {
        openvdb::io::File out(file.path());
        out.write(openvdb::GridPtrVec{grid});
        out.close();
    } catch (const openvdb::Exception& e) {
        throw IoError("cannot write " + path + ": " + e.what());
    }
    file.commit();
}

openvdb::Coord coordOf(const glm::uvec3& cell) { return openvdb::Coord(int(cell.x), int(cell.y), int(cell.z)); }

/// One band block into its leaf: band cells active with their value, the
/// block's other cells in the grid inactive at -W or +W by their label,
/// cells past the grid the background.
void fillLeaf(openvdb::FloatTree::LeafNodeType& leaf, const SparseBand& band, const BandBlock& b) {
    const float w = float(band.halfWidth);
    const glm::uvec3 size = glm::min(glm::uvec3(kSide), band.grid.dims - b.origin);
    std::uint64_t next = b.first;
    for (openvdb::Index n = 0; n < kSide * kSide * kSide; ++n) {
        const std::uint32_t x = n / 64, y = n / 8 % 8, z = n % 8;
        const std::uint64_t bit = std::uint64_t(1) << (n % 64);
        if (x >= size.x || y >= size.y || z >= size.z) leaf.setValueOff(n, w);
        else if (b.band[x] & bit) leaf.setValueOn(n, band.values[next++]);
        else leaf.setValueOff(n, b.inside[x] & bit ? -w : w);
    }
}

/// Whether every block of the node at `node` (in blocks) is a tile inside.
bool nodeInside(const SparseBand& band, const std::vector<bool>& stored, const glm::uvec3& node) {
    if (glm::any(glm::greaterThan(node + kNodeBlocks, band.blockDims))) return false;
    for (std::uint32_t x = 0; x < kNodeBlocks; ++x)
        for (std::uint32_t y = 0; y < kNodeBlocks; ++y)
            for (std::uint32_t z = 0; z < kNodeBlocks; ++z) {
                const glm::uvec3 b = node + glm::uvec3(x, y, z);
                if (stored[band.blockIndex(b)] || !band.tileInside(b)) return false;
            }
    return true;
}

/// The inside tiles: a node's tile where every block of it is inside, else
/// a tile a block (the tree then holds one node per 128^3 cells of interior
/// at most).
void addInsideTiles(openvdb::FloatTree& tree, const SparseBand& band, const std::vector<bool>& stored) {
    const float w = float(band.halfWidth);
    const glm::uvec3 nodes = (band.blockDims + kNodeBlocks - 1u) / kNodeBlocks;
    for (std::uint32_t nx = 0; nx < nodes.x; ++nx)
        for (std::uint32_t ny = 0; ny < nodes.y; ++ny)
            for (std::uint32_t nz = 0; nz < nodes.z; ++nz) {
                const glm::uvec3 node = glm::uvec3(nx, ny, nz) * kNodeBlocks;
                if (nodeInside(band, stored, node)) {
                    tree.addTile(2, coordOf(node * kSide), -w, false);
                    continue;
                }
                const glm::uvec3 end = glm::min(node + kNodeBlocks, band.blockDims);
                for (std::uint32_t x = node.x; x < end.x; ++x)
                    for (std::uint32_t y = node.y; y < end.y; ++y)
                        for (std::uint32_t z = node.z; z < end.z; ++z) {
                            const glm::uvec3 b(x, y, z);
                            if (!stored[band.blockIndex(b)] && band.tileInside(b))
                                tree.addTile(1, coordOf(b * kSide), -w, false);
                        }
            }
}

} // namespace

bool vdbAvailable() { return true; }
std::string vdbLibrary() { return std::string("OpenVDB ") + openvdb::getLibraryVersionString(); }
std::string vdsVersion() { return VDS_VERSION; }

void writeVdb(const std::string& path, const SparseBand& band, const VdbOptions& options) {
    initialise();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(float(band.halfWidth));
    openvdb::FloatTree& tree = grid->tree();
    std::vector<bool> stored(std::size_t(band.blockIndex(band.blockDims - 1u)) + 1);
    {
        openvdb::tree::ValueAccessor<openvdb::FloatTree> access(tree);
        for (const BandBlock& b : band.blocks) {
            fillLeaf(*access.touchLeaf(coordOf(b.origin)), band, b);
            stored[band.blockIndex(b.origin / kSide)] = true;
        }
    }
    addInsideTiles(tree, band, stored);
    tree.prune();
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    describe(*grid, band.grid, band.rule, options, "sdf");
    grid->insertMeta("half_width", openvdb::DoubleMetadata(band.halfWidth));
    writeGrid(path, grid);
}

void writeVdb(const std::string& path, const Grid& grid, const std::uint8_t* cells, Rule rule,
              const VdbOptions& options) {
    checkGrid(grid);
    if (grid.first != glm::uvec3(0u) || (grid.whole != glm::uvec3(0u) && grid.whole != grid.dims))
        throw InvalidArgument("a .vdb holds a whole grid, not a slab of one");
    initialise();
    openvdb::BoolGrid::Ptr out = openvdb::BoolGrid::create(false);
    openvdb::tree::ValueAccessor<openvdb::BoolTree> access(out->tree());
    const glm::uvec3 blocks = (grid.dims + kSide - 1u) / kSide;
    for (std::uint32_t bx = 0; bx < blocks.x; ++bx)
        for (std::uint32_t by = 0; by < blocks.y; ++by)
            for (std::uint32_t bz = 0; bz < blocks.z; ++bz) {
                const glm::uvec3 origin = glm::uvec3(bx, by, bz) * kSide, end = glm::min(origin + kSide, grid.dims);
                std::size_t inside = 0;
                for (std::uint32_t i = origin.x; i < end.x; ++i)
                    for (std::uint32_t j = origin.y; j < end.y; ++j)
                        for (std::uint32_t k = origin.z; k < end.z; ++k) inside += cells[grid.index(i, j, k)] != 0;
                if (inside == 0) continue;
                if (inside == kSide * kSide * kSide) {
                    access.addTile(1, coordOf(origin), true, true);
                    continue;
                }
                openvdb::BoolTree::LeafNodeType& leaf = *access.touchLeaf(coordOf(origin));
                for (std::uint32_t i = origin.x; i < end.x; ++i)
                    for (std::uint32_t j = origin.y; j < end.y; ++j)
                        for (std::uint32_t k = origin.z; k < end.z; ++k)
                            if (cells[grid.index(i, j, k)]) leaf.setValueOn(coordOf({i, j, k}), true);
            }
    access.clear();
    out->tree().prune();
    out->setGridClass(openvdb::GRID_UNKNOWN);
    describe(*out, grid, rule, options, "occupancy");
    writeGrid(path, out);
}

} // namespace vds
