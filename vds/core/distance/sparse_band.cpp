// vds: narrow bands computed sparsely (<vds/sparse_band.h>): the triangles
// mark the 8^3 blocks within the half-width of them, each marked block's
// cells get their exact distance and label, and every other block is a
// tile labelled by one sweep of a grid with a cell per block.
#include <vds/sparse_band.h>

#include <algorithm>
#include <atomic>
#include <bitset>
#include <cmath>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <vds/detail/parallel.h>
#include <vds/error.h>

namespace vds {

namespace {

constexpr std::uint32_t kSide = kBandBlockSide;
/// Triangles a chunk of the marking pass.
constexpr std::size_t kTriangleChunk = 2048;
/// Runs of marked blocks a chunk of the band pass: its values go to one
/// vector, so the chunks' vectors stay few.
constexpr std::size_t kRunChunk = 16;
/// Unmarked blocks a run of marked blocks along z may span: a run's cells
/// are labelled by one sweep of its columns (a column's crossings found once,
/// not once a block), and an unmarked block costs its labels only (no
/// triangle is near it, so its distances are filled without a search).
constexpr std::uint32_t kRunGap = 4;
/// Cells of the tile grid a sweep labels at once: its label bytes.
constexpr std::size_t kTileSlabCells = std::size_t(1) << 24;
/// Bytes of chunks freed between hand-backs of the gather (`gather`).
constexpr std::size_t kReturnBytes = std::size_t(64) << 20;
/// Relative margin by which a triangle's box grows past W, over the grid's
/// largest coordinate: far more than the float rounding of a cell centre
/// (2^-24 relative), so no cell within W of a triangle lies outside it.
constexpr double kMarkMargin = 1.0 / (1 << 20);

void checkSparseGrid(const Grid& grid) {
    if (grid.dims.x == 0 || grid.dims.y == 0 || grid.dims.z == 0)
        throw InvalidArgument("sparse band grid has a zero dimension");
    if (grid.first != glm::uvec3(0u) || (grid.whole != glm::uvec3(0u) && grid.whole != grid.dims))
        throw InvalidArgument("a sparse band covers a whole grid, not a slab of one");
    if (std::uint64_t(grid.dims.x) * grid.dims.y * grid.dims.z > kMaxSparseCells)
        throw InvalidArgument("sparse band grid of " + std::to_string(grid.dims.x) + "x" + std::to_string(grid.dims.y) +
                              "x" + std::to_string(grid.dims.z) + " cells is too large (at most 2^40 cells)");
    for (int a = 0; a < 3; ++a)
        if (!(std::isfinite(grid.box.lo[a]) && std::isfinite(grid.box.hi[a]) && grid.box.lo[a] < grid.box.hi[a]))
            throw InvalidArgument("sparse band grid box is empty or not finite");
}

std::size_t words(std::uint64_t bits) { return std::size_t((bits + 63) / 64); }

/// The grid's blocks in mesh units: block b spans cells [8 b, 8 b + 8) on
/// each axis, the cube lo + [8 b, 8 b + 8) * cell (past the grid's last cell
/// for a partial block).
struct BlockFrame {
    explicit BlockFrame(const Grid& grid) : lo(grid.box.lo), blocks((grid.dims + kSide - 1u) / kSide) {
        cell = (glm::dvec3(grid.box.hi) - lo) / glm::dvec3(grid.dims);
        edge = cell * double(kSide);
    }
    glm::dvec3 centre(const glm::uvec3& b) const { return lo + (glm::dvec3(b) + 0.5) * edge; }
    glm::dvec3 lo, cell, edge;
    glm::uvec3 blocks;
};

/// One bit per block, set from many threads.
class BlockBits {
public:
    explicit BlockBits(std::uint64_t count) : words_(words(count)) {}
    void set(std::uint64_t b) { words_[b / 64].fetch_or(std::uint64_t(1) << (b % 64), std::memory_order_relaxed); }
    void assign(std::uint64_t b, bool on) {
        const std::uint64_t bit = std::uint64_t(1) << (b % 64);
        if (on) words_[b / 64].fetch_or(bit, std::memory_order_relaxed);
        else words_[b / 64].fetch_and(~bit, std::memory_order_relaxed);
    }
    std::size_t wordCount() const { return words_.size(); }
    std::uint64_t word(std::size_t w) const { return words_[w].load(std::memory_order_relaxed); }

private:
    std::vector<std::atomic<std::uint64_t>> words_;
};

/// Marks the blocks that triangle (a, b, c) may be within `reach` of: those
/// its box grown by `reach` meets, less those its plane is farther from.
void markTriangle(const BlockFrame& f, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double reach,
                  BlockBits& marks) {
    glm::uvec3 first, last;
    for (int k = 0; k < 3; ++k) {
        const double lo = (std::min({a[k], b[k], c[k]}) - reach - f.lo[k]) / f.edge[k];
        const double hi = (std::max({a[k], b[k], c[k]}) + reach - f.lo[k]) / f.edge[k];
        if (hi < 0.0 || lo >= double(f.blocks[k])) return;
        first[k] = std::uint32_t(std::max(0.0, std::floor(lo)));
        last[k] = std::uint32_t(std::min(double(f.blocks[k] - 1), std::floor(hi)));
    }
    glm::dvec3 normal = glm::cross(b - a, c - a);
    const double area = glm::length(normal);
    normal = area > 0.0 ? normal / area : glm::dvec3(0.0); // degenerate: the box alone
    const double planeReach = reach + 0.5 * glm::length(f.edge);
    for (std::uint32_t x = first.x; x <= last.x; ++x)
        for (std::uint32_t y = first.y; y <= last.y; ++y)
            for (std::uint32_t z = first.z; z <= last.z; ++z) {
                if (std::abs(glm::dot(normal, f.centre({x, y, z}) - a)) > planeReach) continue;
                marks.set((std::uint64_t(x) * f.blocks.y + y) * f.blocks.z + z);
            }
}

/// The blocks any triangle of `mesh` is within `reach` of, ascending.
std::vector<std::uint64_t> markedBlocks(const BlockFrame& f, MeshView mesh, double reach, unsigned threads) {
    BlockBits marks(std::uint64_t(f.blocks.x) * f.blocks.y * f.blocks.z);
    detail::parallelFor(threads, mesh.triangleCount, kTriangleChunk, [&](std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const glm::uvec3 v = mesh.triangles[t];
            markTriangle(f, mesh.positions[v.x], mesh.positions[v.y], mesh.positions[v.z], reach, marks);
        }
    });
    std::vector<std::uint64_t> marked;
    for (std::size_t w = 0; w < marks.wordCount(); ++w)
        for (std::uint64_t bits = marks.word(w); bits; bits &= bits - 1)
            marked.push_back(std::uint64_t(w) * 64 + std::uint64_t(__builtin_ctzll(bits)));
    return marked;
}

/// Every block's label by its centre: one sweep of the grid of a cell per
/// block, a slab of x layers at a time.
void labelTiles(const ExactClassifier& signs, Rule rule, const BlockFrame& f, unsigned threads, BlockBits& tiles) {
    Grid blocks;
    blocks.box.lo = glm::vec3(f.lo);
    blocks.box.hi = glm::vec3(f.lo + glm::dvec3(f.blocks) * f.edge);
    blocks.dims = f.blocks;
    const std::size_t layer = std::size_t(f.blocks.y) * f.blocks.z;
    const std::uint32_t slab = std::uint32_t(std::clamp<std::size_t>(kTileSlabCells / layer, 1, f.blocks.x));
    std::vector<std::uint8_t> labels(std::size_t(slab) * layer);
    ClassifyOptions classify;
    classify.rule = rule;
    classify.threads = threads;
    for (std::uint32_t i0 = 0; i0 < f.blocks.x; i0 += slab) {
        const std::uint32_t i1 = std::min(f.blocks.x, i0 + slab);
        signs.occupancy(blocks.slabX(i0, i1), labels.data(), classify);
        const std::size_t count = std::size_t(i1 - i0) * layer;
        for (std::size_t c = 0; c < count; ++c)
            if (labels[c]) tiles.set(std::uint64_t(i0) * layer + c);
    }
}

/// What a chunk of the band pass made.
struct ChunkBand {
    std::vector<BandBlock> blocks;
    std::vector<float> values; ///< `blocks`' first counts from the chunk's start
};

/// Marked blocks [begin, end) of the ascending list, all in one column of
/// blocks (the same x and y).
struct Run {
    std::size_t begin, end;
};

/// The marked blocks in runs: the same column of blocks, at most kRunGap
/// unmarked blocks between one and the next.
std::vector<Run> runsOf(const std::vector<std::uint64_t>& marked, std::uint32_t blocksZ) {
    std::vector<Run> runs;
    for (std::size_t m = 0; m < marked.size(); ++m) {
        const bool joins = m > 0 && marked[m] / blocksZ == marked[m - 1] / blocksZ &&
                           marked[m] - marked[m - 1] <= kRunGap + 1;
        if (joins) runs.back().end = m + 1;
        else runs.push_back({m, m + 1});
    }
    return runs;
}

/// The cells of a run of blocks: the dense band of the run's cells alone (a
/// grid of them, their centres the whole grid's: the same floats and signs
/// as the whole dense band), each marked block into `out` when it holds a
/// band cell or labels that differ, otherwise a tile of its one label.
class RunFiller {
public:
    RunFiller(const SignedDistance& distance, const Grid& grid, const BlockFrame& frame, double halfWidth)
        : distance_(distance), grid_(grid), frame_(frame), halfWidth_(halfWidth) {
        options_.threads = 1;
        options_.band = halfWidth;
    }
    void fill(const std::vector<std::uint64_t>& marked, const Run& run, ChunkBand& out, BlockBits& tiles);

private:
    void keep(std::uint64_t index, const Grid& cells, std::uint32_t z0, ChunkBand& out, BlockBits& tiles) const;

    const SignedDistance& distance_;
    const Grid& grid_;
    const BlockFrame& frame_;
    double halfWidth_;
    DistanceGridOptions options_;
    std::vector<float> cells_;
};

void RunFiller::fill(const std::vector<std::uint64_t>& marked, const Run& run, ChunkBand& out, BlockBits& tiles) {
    const std::uint64_t column = marked[run.begin] / frame_.blocks.z;
    const glm::uvec3 origin(std::uint32_t(column / frame_.blocks.y) * kSide, std::uint32_t(column % frame_.blocks.y) * kSide,
                            std::uint32_t(marked[run.begin] % frame_.blocks.z) * kSide);
    const std::uint32_t zEnd = std::min(grid_.dims.z, std::uint32_t(marked[run.end - 1] % frame_.blocks.z + 1) * kSide);
    Grid cells = grid_;
    cells.whole = grid_.dims;
    cells.first = origin;
    cells.dims = glm::uvec3(std::min(kSide, grid_.dims.x - origin.x), std::min(kSide, grid_.dims.y - origin.y), zEnd - origin.z);
    cells_.resize(cells.cellCount());
    distance_.grid(cells, cells_.data(), options_);
    for (std::size_t m = run.begin; m < run.end; ++m)
        keep(marked[m], cells, std::uint32_t(marked[m] % frame_.blocks.z) * kSide - origin.z, out, tiles);
}

/// Block `index`, its cells from z0 on in the run's `cells`.
void RunFiller::keep(std::uint64_t index, const Grid& cells, std::uint32_t z0, ChunkBand& out, BlockBits& tiles) const {
    BandBlock b;
    b.origin = glm::uvec3(cells.first.x, cells.first.y, cells.first.z + z0);
    const std::uint32_t depth = std::min(kSide, cells.dims.z - z0);
    const float background = float(halfWidth_);
    b.first = out.values.size();
    bool any = false;
    std::size_t insideCount = 0, n = 0;
    for (std::uint32_t x = 0; x < cells.dims.x; ++x)
        for (std::uint32_t y = 0; y < cells.dims.y; ++y)
            for (std::uint32_t z = 0; z < depth; ++z, ++n) {
                const std::uint64_t bit = std::uint64_t(1) << (y * kSide + z);
                const float v = cells_[cells.index(x, y, z0 + z)];
                if (std::signbit(v)) b.inside[x] |= bit, ++insideCount;
                if (!(std::abs(v) < background)) continue;
                b.band[x] |= bit;
                out.values.push_back(v);
                any = true;
            }
    if (any || (insideCount != 0 && insideCount != n)) out.blocks.push_back(b);
    else tiles.assign(index, insideCount != 0);
}

/// Hands freed memory back to the system: glibc keeps the small blocks the
/// chunks were made of for reuse, which the band's one array cannot reuse.
void returnFreedMemory() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

/// The chunks' blocks and values, in order, into `band`; each chunk is
/// freed once copied, and the freed memory handed back every
/// kReturnBytes, so that the band is held about once while it is gathered
/// (the array's pages are touched only as they are filled), not twice.
void gather(std::vector<ChunkBand>& chunks, SparseBand& band) {
    std::size_t blockCount = 0, valueCount = 0;
    for (const ChunkBand& c : chunks) blockCount += c.blocks.size(), valueCount += c.values.size();
    try {
        band.blocks.reserve(blockCount);
        band.values.reserve(valueCount);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory("not enough memory for a band of " + std::to_string(valueCount) + " cells");
    }
    std::size_t freed = 0;
    for (ChunkBand& c : chunks) {
        const std::uint64_t offset = band.values.size();
        for (BandBlock b : c.blocks) {
            b.first += offset;
            band.blocks.push_back(b);
        }
        band.values.insert(band.values.end(), c.values.begin(), c.values.end());
        freed += c.values.capacity() * sizeof(float) + c.blocks.capacity() * sizeof(BandBlock);
        c = ChunkBand{};
        if (freed >= kReturnBytes) returnFreedMemory(), freed = 0;
    }
    returnFreedMemory();
}

std::size_t bandBits(const std::uint64_t (&mask)[8], int words, std::uint64_t below) {
    std::size_t count = 0;
    for (int w = 0; w < words; ++w) count += std::bitset<64>(mask[w]).count();
    return count + std::bitset<64>(mask[words] & below).count();
}

} // namespace

const BandBlock* SparseBand::blockOf(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    const std::uint64_t key = blockIndex(glm::uvec3(i, j, k) / kSide);
    const auto at = std::lower_bound(blocks.begin(), blocks.end(), key, [&](const BandBlock& b, std::uint64_t v) {
        return blockIndex(b.origin / kSide) < v;
    });
    return at != blocks.end() && blockIndex(at->origin / kSide) == key ? &*at : nullptr;
}

float SparseBand::value(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    const float background = float(halfWidth);
    const BandBlock* b = blockOf(i, j, k);
    if (!b) return tileInside(glm::uvec3(i, j, k) / kSide) ? -background : background;
    const int x = int(i % kSide);
    const std::uint64_t bit = std::uint64_t(1) << (j % kSide * kSide + k % kSide);
    if (b->band[x] & bit) return values[b->first + bandBits(b->band, x, bit - 1)];
    return b->inside[x] & bit ? -background : background;
}

std::size_t SparseBand::memoryBytes() const {
    return blocks.capacity() * sizeof(BandBlock) + values.capacity() * sizeof(float) +
           tiles.capacity() * sizeof(std::uint64_t);
}

SparseBand sparseBand(const SignedDistance& distance, MeshView mesh, const Grid& grid,
                      const SparseBandOptions& options) {
    if (!(std::isfinite(options.halfWidth) && options.halfWidth > 0.0))
        throw InvalidArgument("the band's half-width must be a finite distance above 0, not " +
                              std::to_string(options.halfWidth));
    checkSparseGrid(grid);
    const ExactClassifier& signs = distance.classifier(); // throws for a flat mesh
    const BlockFrame frame(grid);
    SparseBand band;
    band.grid = grid;
    band.halfWidth = options.halfWidth;
    band.rule = distance.rule();
    band.blockDims = frame.blocks;
    const std::uint64_t blockCount = std::uint64_t(frame.blocks.x) * frame.blocks.y * frame.blocks.z;
    double largest = options.halfWidth;
    for (int a = 0; a < 3; ++a) largest = std::max({largest, std::abs(double(grid.box.lo[a])), std::abs(double(grid.box.hi[a]))});
    const double reach = options.halfWidth + kMarkMargin * largest;
    const std::vector<std::uint64_t> marked = markedBlocks(frame, mesh, reach, options.threads);
    BlockBits tiles(blockCount);
    labelTiles(signs, band.rule, frame, options.threads, tiles);
    const std::vector<Run> runs = runsOf(marked, frame.blocks.z);
    std::vector<ChunkBand> chunks((runs.size() + kRunChunk - 1) / kRunChunk);
    detail::parallelFor(options.threads, runs.size(), kRunChunk, [&](std::size_t begin, std::size_t end) {
        RunFiller filler(distance, grid, frame, options.halfWidth);
        ChunkBand& out = chunks[begin / kRunChunk];
        for (std::size_t r = begin; r < end; ++r) filler.fill(marked, runs[r], out, tiles);
        out.values.shrink_to_fit();
        out.blocks.shrink_to_fit();
    });
    gather(chunks, band);
    band.tiles.resize(tiles.wordCount());
    for (std::size_t w = 0; w < band.tiles.size(); ++w) band.tiles[w] = tiles.word(w);
    return band;
}

Grid voxelSizeGrid(const Box& box, double voxelSize) {
    if (!(std::isfinite(voxelSize) && voxelSize > 0.0))
        throw InvalidArgument("the voxel size must be a finite length above 0, not " + std::to_string(voxelSize));
    Grid grid;
    grid.box = box;
    for (int a = 0; a < 3; ++a) {
        const double cells = std::max(1.0, std::ceil((double(box.hi[a]) - double(box.lo[a])) / voxelSize));
        if (!(cells <= double(std::numeric_limits<std::int32_t>::max())))
            throw InvalidArgument("a voxel size of " + std::to_string(voxelSize) + " makes too many cells");
        grid.dims[a] = std::uint32_t(cells);
        grid.box.hi[a] = float(double(box.lo[a]) + cells * voxelSize);
    }
    checkSparseGrid(grid);
    return grid;
}

} // namespace vds
