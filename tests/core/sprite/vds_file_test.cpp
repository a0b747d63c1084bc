// Tests of the .vds file (vds/src/vds_file.cpp): bit-exact round trips, the
// atomic write, and refusal of every kind of damaged file without a crash.
#include <vds/vds_file.h>

#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <vds/error.h>
#include <vds/npy.h>
#include <vds/sprite.h>

namespace fs = std::filesystem;
using namespace std::string_literals;

namespace {

// ---------------------------------------------------------------- sprites built by hand

/// Appends one column of `(depth, entering)` crossings, already sorted.
void addColumn(vds::Sprite& s, const std::vector<std::pair<float, bool>>& column) {
    for (const auto& [depth, entering] : column) s.crossings.push_back(vds::encodeCrossing(depth, entering));
    s.offsets.push_back(std::uint32_t(s.crossings.size()));
    s.depthComplexity = std::max(s.depthComplexity, std::uint32_t(column.size()));
}

vds::Sprite emptySprite(std::uint32_t resolution, vds::Axis axis = vds::Axis::Z) {
    vds::Sprite s;
    s.grid = vds::makeGrid(vds::Box{{-1.0f, -2.0f, -0.5f}, {3.0f, 1.0f, 1.5f}}, axis, resolution);
    s.offsets.assign(1, 0);
    s.sourceName = "bunny.obj";
    s.sourceTriangles = (std::uint64_t(1) << 40) + 7; // does not fit 32 bits
    s.status = vds::SolidStatus::Open;
    s.validation = "open: 12 boundary edges, 3 non-manifold edges";
    // A placed sprite: every matrix entry distinct, so a transposition shows.
    s.grid.position = {0.25f, -1.5f, 3.0f};
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) s.grid.matrix[c][r] = 0.1f * float(1 + 3 * c + r) + (c == r ? 1.0f : 0.0f);
    return s;
}

/// A small sprite with every special case: empty columns, -0.0 (leaving at
/// depth 0), a crossing at depth 1, ties, and one column of 40 crossings.
vds::Sprite specialSprite(vds::Axis axis = vds::Axis::Z) {
    vds::Sprite s = emptySprite(8, axis);
    const std::size_t columns = std::size_t(s.width()) * s.height();
    std::mt19937 rng(1234);
    for (std::size_t c = 0; c < columns; ++c) {
        std::vector<std::pair<float, bool>> column;
        if (c == 0 || c == columns - 1 || c % 5 == 3) {
            // empty
        } else if (c == 1) {
            column = {{0.0f, false}, {0.0f, true}, {0.5f, false}, {1.0f, true}};
        } else if (c == 2) {
            column = {{1.0f, true}, {1.0f, false}};
        } else if (c == columns / 2) {
            for (int k = 0; k < 40; ++k) column.push_back({float(k / 2) / 20.0f, k % 2 == 0});
        } else {
            float depth = 0.0f;
            const int n = 1 + int(rng() % 6);
            for (int k = 0; k < n; ++k) {
                depth = std::min(1.0f, depth + float(rng() >> 8) * 0x1p-24f * 0.3f);
                column.push_back({depth, (rng() & 1) != 0});
            }
        }
        addColumn(s, column);
    }
    return s;
}

/// What a baker makes of a sphere with a stack of thin plates inside it: most
/// columns have 2 crossings, a few have 8.
vds::Sprite realisticSprite(std::uint32_t resolution) {
    vds::Sprite s = emptySprite(resolution);
    s.status = vds::SolidStatus::Closed;
    for (std::uint32_t j = 0; j < s.height(); ++j) {
        for (std::uint32_t i = 0; i < s.width(); ++i) {
            const float u = (float(i) + 0.5f) / float(s.width()) * 2.0f - 1.0f;
            const float v = (float(j) + 0.5f) / float(s.height()) * 2.0f - 1.0f;
            const float r2 = u * u + v * v;
            std::vector<std::pair<float, bool>> column;
            if (r2 < 0.81f) {
                const float h = 0.5f * std::sqrt(0.81f - r2);
                column.push_back({0.5f - h, true});
                if (std::fabs(u) < 0.1f && std::fabs(v) < 0.1f)
                    for (int k = 0; k < 3; ++k) {
                        column.push_back({0.4f + 0.05f * float(k), false});
                        column.push_back({0.42f + 0.05f * float(k), true});
                    }
                column.push_back({0.5f + h, false});
            }
            addColumn(s, column);
        }
    }
    return s;
}

// ---------------------------------------------------------------- comparisons

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectSameSprite(const vds::Sprite& a, const vds::Sprite& b) {
    EXPECT_EQ(a.grid.axis, b.grid.axis);
    EXPECT_EQ(a.grid.width, b.grid.width);
    EXPECT_EQ(a.grid.height, b.grid.height);
    EXPECT_TRUE(sameBits(a.grid.texelSize, b.grid.texelSize));
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(sameBits(a.grid.box.lo[k], b.grid.box.lo[k])) << k;
        EXPECT_TRUE(sameBits(a.grid.box.hi[k], b.grid.box.hi[k])) << k;
        EXPECT_TRUE(sameBits(a.grid.position[k], b.grid.position[k])) << k;
    }
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_TRUE(sameBits(a.grid.matrix[c][r], b.grid.matrix[c][r])) << c << r;
    EXPECT_EQ(a.depthComplexity, b.depthComplexity);
    EXPECT_EQ(a.offsets, b.offsets);
    ASSERT_EQ(a.crossings.size(), b.crossings.size());
    EXPECT_TRUE(a.crossings.empty() ||
                std::memcmp(a.crossings.data(), b.crossings.data(), a.crossings.size() * sizeof(float)) == 0);
    EXPECT_EQ(a.sourceName, b.sourceName);
    EXPECT_EQ(a.sourceTriangles, b.sourceTriangles);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.validation, b.validation);
}

bool identical(const vds::Sprite& a, const vds::Sprite& b) {
    bool same = a.grid.axis == b.grid.axis && a.grid.width == b.grid.width && a.grid.height == b.grid.height &&
                sameBits(a.grid.texelSize, b.grid.texelSize) && a.depthComplexity == b.depthComplexity &&
                a.offsets == b.offsets && a.crossings.size() == b.crossings.size() &&
                a.sourceName == b.sourceName && a.sourceTriangles == b.sourceTriangles && a.status == b.status &&
                a.validation == b.validation;
    for (int k = 0; same && k < 3; ++k)
        same = sameBits(a.grid.box.lo[k], b.grid.box.lo[k]) && sameBits(a.grid.box.hi[k], b.grid.box.hi[k]) &&
               sameBits(a.grid.position[k], b.grid.position[k]);
    for (int k = 0; same && k < 9; ++k) same = sameBits(a.grid.matrix[k / 3][k % 3], b.grid.matrix[k / 3][k % 3]);
    return same && (a.crossings.empty() ||
                    std::memcmp(a.crossings.data(), b.crossings.data(), a.crossings.size() * sizeof(float)) == 0);
}

// ---------------------------------------------------------------- files

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << p;
}

std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// Offset of `needle` in `bytes`; fails the test if absent.
std::size_t find(const std::string& bytes, const std::string& needle) {
    const std::size_t at = bytes.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    return at == std::string::npos ? 0 : at;
}

/// Offset of the value of header attribute `name`: name\0 type\0 int32 size, value.
std::size_t attributeValue(const std::string& bytes, const std::string& name, const std::string& type) {
    return find(bytes, name + '\0' + type + '\0') + name.size() + 1 + type.size() + 1 + 4;
}

class VdsFileTest : public testing::Test {
protected:
    void SetUp() override {
        static std::atomic<int> counter{0};
        dir_ = fs::path(testing::TempDir()) /
               ("vds_file_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    /// Reads `bytes` as a .vds file; returns the FormatError message, or ""
    /// if the file was read (then `*out` holds the sprite).
    std::string readDamaged(const std::string& bytes, vds::Sprite* out = nullptr) {
        const std::string p = path("damaged.vds");
        writeBytes(p, bytes);
        try {
            vds::Sprite s = vds::readSprite(p);
            if (out) *out = std::move(s);
            return "";
        } catch (const vds::FormatError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_EQ(message.rfind(p + ": ", 0), 0u) << message;
            return message.empty() ? "?" : message;
        }
    }

    fs::path dir_;
};

// ---------------------------------------------------------------- round trips

TEST_F(VdsFileTest, RoundTripIsBitExact) {
    const vds::Sprite s = specialSprite();
    ASSERT_NO_THROW(s.checkConsistent());
    vds::writeSprite(s, path("a.vds"));
    const vds::Sprite r = vds::readSprite(path("a.vds"));
    expectSameSprite(s, r);
    // The leaving crossing at depth 0 keeps its sign.
    ASSERT_GE(r.crossings.size(), 2u);
    EXPECT_TRUE(std::signbit(r.crossings[0]));
    EXPECT_FALSE(vds::crossingEnters(r.crossings[0]));
    EXPECT_TRUE(vds::crossingEnters(r.crossings[1]));
    EXPECT_EQ(r.depthComplexity, 40u);
    EXPECT_EQ(r.sourceTriangles, (std::uint64_t(1) << 40) + 7);
}

// Encoding to memory gives exactly the file's bytes, and decoding them (or a
// damaged copy) behaves as reading the file does.
TEST_F(VdsFileTest, EncodeAndDecodeInMemoryMatchTheFile) {
    const vds::Sprite s = specialSprite();
    const std::vector<char> bytes = vds::encodeSprite(s);
    vds::writeSprite(s, path("m.vds"));
    std::ifstream in(path("m.vds"), std::ios::binary);
    const std::vector<char> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(bytes, file);
    expectSameSprite(s, vds::decodeSprite(bytes.data(), bytes.size()));
    EXPECT_THROW(vds::decodeSprite(bytes.data(), bytes.size() / 2, "half"), vds::FormatError);
    EXPECT_THROW(vds::decodeSprite(bytes.data(), 0, "nothing"), vds::FormatError);
    std::vector<char> flipped = bytes;
    flipped[flipped.size() - 9] ^= 0x20;
    try {
        vds::decodeSprite(flipped.data(), flipped.size(), "flipped");
        ADD_FAILURE() << "a flipped byte was not noticed";
    } catch (const vds::FormatError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("flipped: ", 0), 0u) << e.what();
    }
}

TEST_F(VdsFileTest, RoundTripEveryAxis) {
    for (vds::Axis axis : {vds::Axis::X, vds::Axis::Y, vds::Axis::Z}) {
        const vds::Sprite s = specialSprite(axis);
        vds::writeSprite(s, path("axis.vds"));
        expectSameSprite(s, vds::readSprite(path("axis.vds")));
    }
}

TEST_F(VdsFileTest, RoundTripWithoutCrossings) {
    vds::Sprite s = emptySprite(5);
    s.sourceName.clear();
    s.validation.clear();
    s.sourceTriangles = 0;
    for (std::size_t c = 0, n = std::size_t(s.width()) * s.height(); c < n; ++c) addColumn(s, {});
    vds::writeSprite(s, path("empty.vds"));
    const vds::Sprite r = vds::readSprite(path("empty.vds"));
    expectSameSprite(s, r);
    EXPECT_TRUE(r.crossings.empty());
    EXPECT_EQ(r.depthComplexity, 0u);
}

TEST_F(VdsFileTest, RoundTripLargeSprite) {
    // More rows than one OpenEXR chunk (16) and one read batch.
    const vds::Sprite s = realisticSprite(300);
    vds::writeSprite(s, path("large.vds"));
    expectSameSprite(s, vds::readSprite(path("large.vds")));
}

TEST_F(VdsFileTest, FileIsSmallerThanDenseTexture) {
    const vds::Sprite s = realisticSprite(128);
    EXPECT_EQ(s.depthComplexity, 8u);
    vds::writeSprite(s, path("sphere.vds"));
    const std::uintmax_t size = fs::file_size(path("sphere.vds"));
    EXPECT_LT(size, s.denseBytes() / 2) << "dense " << s.denseBytes();
    EXPECT_LT(size, s.memoryBytes()) << "in memory " << s.memoryBytes();
}

// ---------------------------------------------------------------- writing

TEST_F(VdsFileTest, ExistingFileIsReplacedWhole) {
    const vds::Sprite big = realisticSprite(64);
    const vds::Sprite small = specialSprite();
    vds::writeSprite(small, path("fresh.vds"));
    const std::string fresh = readBytes(path("fresh.vds"));

    vds::writeSprite(big, path("target.vds"));
    ASSERT_GT(fs::file_size(path("target.vds")), fresh.size());
    vds::writeSprite(small, path("target.vds"));
    EXPECT_EQ(readBytes(path("target.vds")), fresh);
    expectSameSprite(small, vds::readSprite(path("target.vds")));

    writeBytes(path("junk.vds"), std::string(100000, 'x'));
    vds::writeSprite(small, path("junk.vds"));
    EXPECT_EQ(readBytes(path("junk.vds")), fresh);
    EXPECT_EQ(entries(dir_), (std::vector<std::string>{"fresh.vds", "junk.vds", "target.vds"}));
}

TEST_F(VdsFileTest, WriteIntoMissingDirectoryThrowsIoError) {
    const std::string target = path("no/such/dir/a.vds");
    try {
        vds::writeSprite(specialSprite(), target);
        FAIL() << "no exception";
    } catch (const vds::IoError& e) {
        EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
    }
    EXPECT_TRUE(entries(dir_).empty());
}

TEST_F(VdsFileTest, FailedRenameLeavesNoTemporary) {
    // The target is a non-empty directory: the temporary is written, the
    // rename fails, and the temporary must go.
    fs::create_directories(dir_ / "taken.vds" / "inside");
    EXPECT_THROW(vds::writeSprite(specialSprite(), path("taken.vds")), vds::IoError);
    EXPECT_EQ(entries(dir_), std::vector<std::string>{"taken.vds"});
}

// A symlink is written through: the file it names is replaced atomically
// (the temporary beside that file), the link itself kept.
TEST_F(VdsFileTest, SymlinkIsWrittenThroughAndKept) {
    const vds::Sprite small = specialSprite();
    vds::writeSprite(small, path("fresh.vds"));
    const std::string fresh = readBytes(path("fresh.vds"));
    fs::create_directories(dir_ / "real");
    writeBytes(dir_ / "real" / "target.vds", "old contents");
    fs::create_symlink("real/target.vds", dir_ / "link.vds");   // relative
    fs::create_symlink(dir_ / "link.vds", dir_ / "chain.vds");   // absolute, to a link
    vds::writeSprite(small, path("chain.vds"));
    EXPECT_TRUE(fs::is_symlink(dir_ / "chain.vds"));
    EXPECT_TRUE(fs::is_symlink(dir_ / "link.vds"));
    EXPECT_EQ(readBytes(dir_ / "real" / "target.vds"), fresh);
    EXPECT_EQ(entries(dir_ / "real"), std::vector<std::string>{"target.vds"}); // no temporary left
    // A dangling link makes the file it names, as a shell's '>' does.
    fs::create_symlink("real/new.vds", dir_ / "dangling.vds");
    vds::writeSprite(small, path("dangling.vds"));
    EXPECT_TRUE(fs::is_symlink(dir_ / "dangling.vds"));
    EXPECT_EQ(readBytes(dir_ / "real" / "new.vds"), fresh);
}

TEST_F(VdsFileTest, SymlinkLoopAndDirectoryAreRefused) {
    fs::create_symlink("b.vds", dir_ / "a.vds");
    fs::create_symlink("a.vds", dir_ / "b.vds");
    EXPECT_THROW(vds::writeSprite(specialSprite(), path("a.vds")), vds::IoError);
    fs::create_directories(dir_ / "empty.vds");
    try {
        vds::writeNpy(path("empty.vds"), "|b1", {1}, "\1", 1);
        ADD_FAILURE() << "a directory was written";
    } catch (const vds::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_directory(dir_ / "empty.vds"));
    EXPECT_EQ(entries(dir_), (std::vector<std::string>{"a.vds", "b.vds", "empty.vds"}));
}

// A FIFO is written to, never replaced: a reader on it gets the bytes.
TEST_F(VdsFileTest, FifoIsWrittenDirectly) {
    const vds::Sprite small = specialSprite();
    const std::vector<char> expected = vds::encodeSprite(small);
    ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
    std::string got;
    std::thread reader([&] { got = readBytes(dir_ / "pipe"); });
    vds::writeSprite(small, path("pipe"));
    reader.join();
    EXPECT_EQ(got, std::string(expected.begin(), expected.end()));
    EXPECT_TRUE(fs::is_fifo(dir_ / "pipe"));
    EXPECT_EQ(entries(dir_), std::vector<std::string>{"pipe"});
}

// A device is written to in place: a null device (made here, not /dev's)
// stays a device; a socket cannot be opened and stays a socket.
TEST_F(VdsFileTest, DeviceAndSocketAreNeverReplaced) {
    if (::mknod(path("null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
        vds::writeSprite(specialSprite(), path("null"));
        vds::writeNpy(path("null"), "|b1", {1}, "\1", 1);
        EXPECT_TRUE(fs::is_character_file(dir_ / "null"));
    }
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(fd, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string socketPath = path("socket");
    ASSERT_LT(socketPath.size(), sizeof address.sun_path);
    std::memcpy(address.sun_path, socketPath.c_str(), socketPath.size() + 1);
    ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    EXPECT_THROW(vds::writeSprite(specialSprite(), socketPath), vds::IoError);
    EXPECT_TRUE(fs::is_socket(dir_ / "socket"));
    ::close(fd);
}

// Bytes after the last chunk: appended data, or two sprites joined, are
// refused with one line saying how many (they were read as the first sprite).
TEST_F(VdsFileTest, TrailingBytesAreRefused) {
    const std::vector<char> bytes = vds::encodeSprite(specialSprite());
    const std::string one(bytes.begin(), bytes.end());
    EXPECT_EQ(readDamaged(one), "");
    const std::string appended = readDamaged(one + "x");
    EXPECT_NE(appended.find("1 byte follows the sprite's last chunk (" + std::to_string(one.size()) + " bytes)"),
              std::string::npos)
        << appended;
    EXPECT_NE(readDamaged(one + one).find(std::to_string(one.size()) + " bytes follow"), std::string::npos);
    EXPECT_THROW(vds::decodeSprite(bytes.data(), bytes.size() - 1), vds::FormatError); // and one short, as before
}

TEST_F(VdsFileTest, InconsistentSpriteIsNotWritten) {
    vds::Sprite s = specialSprite();
    s.depthComplexity += 1;
    EXPECT_THROW(vds::writeSprite(s, path("bad.vds")), vds::FormatError);
    s = specialSprite();
    s.offsets.pop_back();
    EXPECT_THROW(vds::writeSprite(s, path("bad.vds")), vds::FormatError);
    EXPECT_TRUE(entries(dir_).empty());
}

// ---------------------------------------------------------------- reading bad files

TEST_F(VdsFileTest, MissingFileThrowsIoError) {
    EXPECT_THROW(vds::readSprite(path("missing.vds")), vds::IoError);
    EXPECT_THROW(vds::readSprite(dir_.string()), vds::IoError); // a directory
}

TEST_F(VdsFileTest, NonVdsFilesThrowFormatError) {
    EXPECT_NE(readDamaged(""), "");
    EXPECT_NE(readDamaged("v/1"), "");
    EXPECT_NE(readDamaged("# not a sprite\nv 0 0 0\nf 1 2 3\n"), "");
    static const unsigned char png[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00,
        0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0x3a, 0x7e, 0x9b, 0x55, 0x00,
        0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60, 0x00, 0x00, 0x00, 0x02, 0x00, 0x01,
        0x48, 0xaf, 0xa4, 0x71, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    EXPECT_NE(readDamaged(std::string(reinterpret_cast<const char*>(png), sizeof png)), "");
}

TEST_F(VdsFileTest, RandomBytesThrowFormatError) {
    std::mt19937 rng(42);
    for (std::size_t size : {1u, 7u, 8u, 100u, 4096u, 70000u}) {
        std::string bytes(size, '\0');
        for (char& c : bytes) c = char(rng());
        EXPECT_NE(readDamaged(bytes), "") << size;
        // Random bytes behind a valid OpenEXR deep scanline magic and version field.
        if (size > 8) {
            std::memcpy(&bytes[0], "\x76\x2f\x31\x01\x02\x08\x00\x00", 8);
            EXPECT_NE(readDamaged(bytes), "") << size;
        }
    }
}

TEST_F(VdsFileTest, EveryTruncationThrowsFormatError) {
    vds::writeSprite(specialSprite(), path("whole.vds"));
    const std::string whole = readBytes(path("whole.vds"));
    ASSERT_GT(whole.size(), 200u);
    // Every cut in the header and the chunk table, then every third one.
    for (std::size_t length = 0; length < whole.size(); length += length < 1024 ? 1 : 3)
        EXPECT_NE(readDamaged(whole.substr(0, length)), "") << "cut at " << length << " of " << whole.size();
    EXPECT_NE(readDamaged(whole.substr(0, whole.size() - 1)), "");
}

TEST_F(VdsFileTest, ByteFlipsAreRefusedOrHarmless) {
    // Any single damaged byte either is refused or (in parts of the OpenEXR
    // header the sprite does not use, or the recoverable chunk table) leaves
    // the sprite exactly as written; it never crashes or yields another sprite.
    const vds::Sprite s = specialSprite();
    vds::writeSprite(s, path("whole.vds"));
    const std::string whole = readBytes(path("whole.vds"));
    int refused = 0;
    for (std::size_t at = 0; at < whole.size(); ++at) {
        for (unsigned mask : {0x01u, 0xffu}) {
            std::string bytes = whole;
            bytes[at] = char(bytes[at] ^ char(mask));
            vds::Sprite r;
            if (readDamaged(bytes, &r).empty())
                EXPECT_TRUE(identical(s, r)) << "byte " << at << " ^ " << mask;
            else
                ++refused;
        }
    }
    EXPECT_GT(refused, int(whole.size()));
}

TEST_F(VdsFileTest, FlippedDataByteThrowsFormatError) {
    const vds::Sprite s = realisticSprite(32);
    vds::writeSprite(s, path("whole.vds"));
    const std::string whole = readBytes(path("whole.vds"));
    // The middle of the file is compressed samples of the middle rows.
    for (std::size_t at : {whole.size() / 2, whole.size() / 2 + 7, whole.size() * 3 / 5}) {
        std::string bytes = whole;
        bytes[at] = char(bytes[at] ^ 0x10);
        EXPECT_NE(readDamaged(bytes), "") << "byte " << at << " of " << whole.size();
    }
}

TEST_F(VdsFileTest, EditedAttributesAreDetected) {
    vds::writeSprite(specialSprite(), path("whole.vds"));
    const std::string whole = readBytes(path("whole.vds"));

    std::string bytes = whole; // same length, other name: only the checksum can tell
    bytes[find(bytes, "bunny.obj")] = 'B';
    EXPECT_NE(readDamaged(bytes).find("checksum"), std::string::npos);

    bytes = whole;
    bytes[attributeValue(bytes, "vds.status", "int")] = 0; // Open -> Closed
    EXPECT_NE(readDamaged(bytes).find("checksum"), std::string::npos);

    bytes = whole;
    bytes[attributeValue(bytes, "vds.formatVersion", "int")] = 4;
    EXPECT_NE(readDamaged(bytes).find("format version 4"), std::string::npos);

    bytes = whole; // read as version 3, which hashes a distance grid too
    bytes[attributeValue(bytes, "vds.formatVersion", "int")] = 3;
    EXPECT_NE(readDamaged(bytes).find("checksum"), std::string::npos);

    bytes = whole;
    bytes[attributeValue(bytes, "vds.depthComplexity", "int")] = 41;
    EXPECT_NE(readDamaged(bytes).find("depthComplexity"), std::string::npos);

    bytes = whole;
    bytes[attributeValue(bytes, "vds.axis", "int")] = 7;
    EXPECT_NE(readDamaged(bytes).find("vds.axis"), std::string::npos);

    bytes = whole;
    bytes[find(bytes, "vds.texelSize") + 12] = 'f'; // renamed: the attribute is missing
    EXPECT_NE(readDamaged(bytes).find("missing attribute vds.texelSize"), std::string::npos);

    bytes = whole;
    bytes[find(bytes, "vds.texelSize\0float"s) + 16] = 'a'; // "flaat": an unknown type
    EXPECT_NE(readDamaged(bytes).find("vds.texelSize has type"), std::string::npos);

    bytes = whole;
    bytes[find(bytes, "vds.checksum\0string"s) + 13 + 7 + 4] ^= 1;
    EXPECT_NE(readDamaged(bytes), "");
}

TEST_F(VdsFileTest, HeaderAttributesAreCheckedBeforeOpenExrReadsThem) {
    // Found by fuzz/vds_file_fuzzer.cpp: OpenEXR sizes a string attribute's
    // value as declared before reading it, so 2 GB were claimed and zeroed
    // for a 1 KB file. The reader now walks the attributes first.
    vds::writeSprite(specialSprite(), path("whole.vds"));
    const std::string whole = readBytes(path("whole.vds"));
    std::string bytes = whole;
    const std::size_t size = attributeValue(bytes, "vds.validation", "string") - 4;
    const unsigned char huge[4] = {0xf0, 0xff, 0xff, 0x7f}; // 2^31 - 16, little-endian
    for (int k = 0; k < 4; ++k) bytes[size + std::size_t(k)] = char(huge[k]);
    EXPECT_NE(readDamaged(bytes).find(": header at byte " + std::to_string(size + 4) +
                                      ": attribute vds.validation declares 2147483632 bytes, more than the "),
              std::string::npos);

    // A fixed-size type declaring another size would make OpenEXR's walk and
    // the file's part ways.
    bytes = whole;
    bytes[attributeValue(bytes, "vds.axis", "int") - 4] = 8;
    EXPECT_NE(readDamaged(bytes).find("attribute vds.axis of type int declares 8 bytes, not 4"), std::string::npos);

    // Found next: a channel list shorter than its declared size. OpenEXR reads
    // channels up to their terminator, then took the leftover bytes for the
    // next attribute, whose "size" asked for 1.6 GB. This is the fuzzer's
    // 77-byte file.
    const std::string channels("v/1\x01\x02\x08\x00\x00"
                               "channels\x00"
                               "chlist\x00,\x00\x00\x00\xa6\xff\xf7unt\x00in\x00"
                               "comprex\x00m33f\x00$\x00\xff\xff_v/1v/\x01\x02`\x00\x00\x08\x0ez\x00z\x00\x00"
                               "0\x00\x86"
                               "a",
                               77);
    EXPECT_NE(readDamaged(channels).find("attribute channels of type chlist"), std::string::npos)
        << readDamaged(channels);
    bytes = whole;
    bytes[attributeValue(bytes, "channels", "chlist") - 4] += 4; // the list now ends 4 bytes before its size
    EXPECT_NE(readDamaged(bytes).find("attribute channels of type chlist"), std::string::npos) << readDamaged(bytes);

    // A name that is not terminated where OpenEXR stops reading it.
    bytes = whole;
    const std::size_t name = find(bytes, "vds.validation");
    std::fill(bytes.begin() + std::ptrdiff_t(name), bytes.begin() + std::ptrdiff_t(name) + 40, 'x');
    EXPECT_NE(readDamaged(bytes).find("an attribute name is not terminated within 31 bytes"), std::string::npos)
        << readDamaged(bytes);

    // The same checks from memory, with the name given in place of a path.
    try {
        vds::decodeSprite(bytes.data(), bytes.size(), "in-memory.vds");
        ADD_FAILURE() << "damaged bytes read";
    } catch (const vds::FormatError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("in-memory.vds: header at byte", 0), 0u) << e.what();
    }
    expectSameSprite(vds::decodeSprite(whole.data(), whole.size(), "in-memory.vds"), vds::readSprite(path("whole.vds")));
}

// ---------------------------------------------------------------- the distance grid (version 3)

/// `s` with a small distance grid of every kind of value: negative,
/// positive, -0.0, 0, and values that differ in the last bit only.
vds::Sprite withDistance(vds::Sprite s) {
    s.distance.grid.box = {{-1.25f, -2.5f, -0.75f}, {3.5f, 1.25f, 1.75f}};
    s.distance.grid.dims = {3, 4, 5};
    for (std::size_t c = 0; c < s.distance.grid.cellCount(); ++c)
        s.distance.cells.push_back(c == 0 ? -0.0f : c == 1 ? 0.0f : std::nextafter(0.1f * float(c) - 2.0f, 9.0f));
    return s;
}

int storedVersion(const std::string& bytes) {
    return int(std::uint8_t(bytes[attributeValue(bytes, "vds.formatVersion", "int")]));
}

TEST_F(VdsFileTest, DistanceGridRoundTripsAsVersion3) {
    const vds::Sprite s = withDistance(specialSprite());
    vds::writeSprite(s, path("d.vds"));
    EXPECT_EQ(storedVersion(readBytes(path("d.vds"))), 3);
    const vds::Sprite r = vds::readSprite(path("d.vds"));
    expectSameSprite(s, r);
    EXPECT_EQ(r.distance.grid.dims, s.distance.grid.dims);
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(sameBits(r.distance.grid.box.lo[k], s.distance.grid.box.lo[k])) << k;
        EXPECT_TRUE(sameBits(r.distance.grid.box.hi[k], s.distance.grid.box.hi[k])) << k;
    }
    ASSERT_EQ(r.distance.cells.size(), s.distance.cells.size());
    for (std::size_t c = 0; c < s.distance.cells.size(); ++c)
        EXPECT_TRUE(sameBits(r.distance.cells[c], s.distance.cells[c])) << c;
    // Without a grid the file stays version 2, which older readers read.
    vds::writeSprite(specialSprite(), path("plain.vds"));
    EXPECT_EQ(storedVersion(readBytes(path("plain.vds"))), 2);
    EXPECT_TRUE(vds::readSprite(path("plain.vds")).distance.empty());
}

TEST_F(VdsFileTest, MalformedDistanceGridIsNotWritten) {
    vds::Sprite s = withDistance(specialSprite());
    s.distance.cells.pop_back();
    EXPECT_THROW(vds::writeSprite(s, path("bad.vds")), vds::FormatError);
    s = withDistance(specialSprite());
    s.distance.cells[7] = std::nanf("");
    EXPECT_THROW(vds::writeSprite(s, path("bad.vds")), vds::FormatError);
    s = withDistance(specialSprite());
    s.distance.grid.box.hi.y = s.distance.grid.box.lo.y;
    EXPECT_THROW(vds::writeSprite(s, path("bad.vds")), vds::FormatError);
    EXPECT_TRUE(entries(dir_).empty());
}

TEST_F(VdsFileTest, CorruptedDistanceGridIsRefusedWithOneLine) {
    vds::writeSprite(withDistance(specialSprite()), path("whole.vds"));
    const std::string whole = readBytes(path("whole.vds"));

    std::string bytes = whole; // a distance flipped in its last bit: only the checksum can tell
    bytes[attributeValue(bytes, "vds.distance", "floatvector") + 4 * 9] ^= 1;
    EXPECT_NE(readDamaged(bytes).find("checksum mismatch"), std::string::npos) << readDamaged(bytes);

    bytes = whole; // more cells claimed than the attribute holds
    bytes[attributeValue(bytes, "vds.distanceDims", "v3i")] = 4;
    EXPECT_NE(readDamaged(bytes).find("attribute vds.distance holds 60 floats, not the 80 cells of vds.distanceDims"),
              std::string::npos)
        << readDamaged(bytes);

    bytes = whole;
    bytes[attributeValue(bytes, "vds.distanceDims", "v3i") + 4] = 0;
    EXPECT_NE(readDamaged(bytes).find("attribute vds.distanceDims holds 0, expected 1 to 1024"), std::string::npos)
        << readDamaged(bytes);

    bytes = whole; // renamed: one of the three is missing
    bytes[find(bytes, "vds.distanceBox") + 4] = 'D';
    EXPECT_NE(readDamaged(bytes).find("the distance grid needs all of"), std::string::npos) << readDamaged(bytes);

    bytes = whole; // a box of five floats
    bytes[attributeValue(bytes, "vds.distanceBox", "floatvector") - 4] = 20;
    EXPECT_NE(readDamaged(bytes), "");
}

} // namespace
