// The mesh and point readers, on files built in code: every format, the
// binary/ASCII twins, non-manifold and untidy meshes read as written, and
// malformed, truncated and absurd files refused with their line or byte.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <tuple>

#include <unistd.h>

#include <gtest/gtest.h>

#include <vds/error.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/mesh_io.h>
#include "solids.h"

namespace vds {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
    const fs::path d = fs::temp_directory_path() / ("vds_mesh_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string boxObj() {
    const auto box = solids::box({0, 0, 0}, {1, 2, 3});
    std::string s;
    for (const auto& v : box.mesh.positions)
        s += "v " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "\n";
    for (const auto& t : box.mesh.triangles)
        s += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    return s;
}

/// Shortest text that reads back as the same float.
std::string num(float v) {
    char s[32];
    std::snprintf(s, sizeof s, "%.9g", double(v));
    return s;
}

std::string objText(const TriangleMesh& m) {
    std::string s = "# written by the test\n";
    for (const auto& v : m.positions) s += "v " + num(v.x) + " " + num(v.y) + " " + num(v.z) + "\n";
    for (const auto& t : m.triangles)
        s += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    return s;
}

std::string offText(const TriangleMesh& m) {
    std::string s = "OFF\n" + std::to_string(m.positions.size()) + " " + std::to_string(m.triangles.size()) + " 0\n";
    for (const auto& v : m.positions) s += num(v.x) + " " + num(v.y) + " " + num(v.z) + "\n";
    for (const auto& t : m.triangles)
        s += "3 " + std::to_string(t.x) + " " + std::to_string(t.y) + " " + std::to_string(t.z) + "\n";
    return s;
}

/// Appends `v` as `bytes` bytes in the given byte order.
template <class T> void put(std::string& out, T v, bool bigEndian) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof b);
    if (bigEndian) std::reverse(b, b + sizeof b);
    out.append(b, sizeof b);
}

enum class PlyEncoding { Ascii, Little, Big };

/// A PLY file of `m` with the clutter real files carry: comments, normals
/// and colours on the vertices, an `edge` element between vertices and faces,
/// a flags byte after each face's list. Coordinates as float or double,
/// face lists with uchar counts and int indices or ushort counts and uint
/// indices.
std::string plyText(const TriangleMesh& m, PlyEncoding encoding, bool doubles, bool wideLists) {
    const char* formats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    std::string s = "ply\nformat " + std::string(formats[int(encoding)]) + " 1.0\ncomment made in a test\n";
    s += "element vertex " + std::to_string(m.positions.size()) + "\n";
    for (const char* c : {"x", "y", "z"}) s += std::string("property ") + (doubles ? "double " : "float ") + c + "\n";
    s += "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n";
    s += "element edge 1\nproperty int vertex1\nproperty int vertex2\n";
    s += "element face " + std::to_string(m.triangles.size()) + "\n";
    s += wideLists ? "property list ushort uint vertex_indices\n" : "property list uchar int vertex_indices\n";
    s += "property uchar flags\nend_header\n";
    const bool big = encoding == PlyEncoding::Big;
    if (encoding == PlyEncoding::Ascii) {
        for (const auto& v : m.positions) {
            for (float c : {v.x, v.y, v.z}) {
                char t[40];
                std::snprintf(t, sizeof t, doubles ? "%.17g " : "%.9g ", double(c));
                s += t;
            }
            s += "0 0 1 200\n";
        }
        s += "0 1\n";
        for (const auto& t : m.triangles)
            s += "3 " + std::to_string(t.x) + " " + std::to_string(t.y) + " " + std::to_string(t.z) + " 5\n";
        return s;
    }
    for (const auto& v : m.positions) {
        for (float c : {v.x, v.y, v.z}) doubles ? put(s, double(c), big) : put(s, c, big);
        for (float n : {0.0f, 0.0f, 1.0f}) put(s, n, big);
        put(s, std::uint8_t(200), big);
    }
    put(s, std::int32_t(0), big);
    put(s, std::int32_t(1), big);
    for (const auto& t : m.triangles) {
        wideLists ? put(s, std::uint16_t(3), big) : put(s, std::uint8_t(3), big);
        for (std::uint32_t i : {t.x, t.y, t.z}) wideLists ? put(s, i, big) : put(s, std::int32_t(i), big);
        put(s, std::uint8_t(5), big);
    }
    return s;
}

std::string stlAscii(const TriangleMesh& m) {
    std::string s = "solid test\n";
    for (const auto& t : m.triangles) {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for (std::uint32_t i : {t.x, t.y, t.z}) {
            const glm::vec3& v = m.positions[i];
            s += "      vertex " + num(v.x) + " " + num(v.y) + " " + num(v.z) + "\n";
        }
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid test\n";
}

std::string stlBinary(const TriangleMesh& m, const std::string& header = "binary STL made in a test") {
    std::string s = header;
    s.resize(80, ' ');
    put(s, std::uint32_t(m.triangles.size()), false);
    for (const auto& t : m.triangles) {
        for (int k = 0; k < 3; ++k) put(s, 0.0f, false);
        for (std::uint32_t i : {t.x, t.y, t.z})
            for (int k = 0; k < 3; ++k) put(s, m.positions[i][k], false);
        put(s, std::uint16_t(0), false);
    }
    return s;
}

TriangleMesh parse(const std::string& bytes, MeshFormat format, const std::string& name = "test") {
    return parseMesh(bytes.data(), bytes.size(), format, name);
}

/// The FormatError message `read` throws; fails the test if it throws none.
std::string formatError(const std::function<void()>& read) {
    try {
        read();
    } catch (const FormatError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        return what;
    }
    ADD_FAILURE() << "no FormatError";
    return {};
}

std::string parseError(const std::string& bytes, MeshFormat format) {
    return formatError([&] { parse(bytes, format, "m"); });
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b, const char* what) {
    EXPECT_EQ(a.positions, b.positions) << what;
    EXPECT_EQ(a.triangles, b.triangles) << what;
}

/// The sphere with its shared vertices welded by position: an indexed mesh
/// whose every corner is referenced by index, as the readers keep it.
TriangleMesh testMesh() { return solids::sphere({0.25f, -1.5f, 3.0f}, 1.75f, 12).mesh; }

TEST(LoadMesh, ReadsObjPlyStlAndOff) {
    const fs::path d = tempDir();
    writeText(d / "box.obj", boxObj());
    const TriangleMesh obj = loadMesh((d / "box.obj").string());
    EXPECT_EQ(obj.triangles.size(), 12u);
    EXPECT_TRUE(validateMesh(obj).closed());
    EXPECT_EQ(obj.name, "box.obj");

    // OFF with quads: fan-triangulated.
    writeText(d / "cube.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                              "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n");
    const TriangleMesh off = loadMesh((d / "cube.off").string());
    EXPECT_EQ(off.triangles.size(), 12u);
    EXPECT_TRUE(validateMesh(off).closed()) << validateMesh(off).summary();

    writeText(d / "tet.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const TriangleMesh ply = loadMesh((d / "tet.ply").string());
    EXPECT_EQ(ply.triangles.size(), 4u);
    EXPECT_TRUE(validateMesh(ply).closed());

    std::string stl = "solid t\n";
    const glm::vec3 v[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& t : f) {
        stl += "facet normal 0 0 0\nouter loop\n";
        for (int k : t)
            stl += "vertex " + std::to_string(v[k].x) + " " + std::to_string(v[k].y) + " " + std::to_string(v[k].z) + "\n";
        stl += "endloop\nendfacet\n";
    }
    writeText(d / "tet.stl", stl + "endsolid t\n");
    const TriangleMesh st = loadMesh((d / "tet.stl").string());
    EXPECT_EQ(st.triangles.size(), 4u);
    EXPECT_TRUE(validateMesh(st).closed()) << validateMesh(st).summary();
    fs::remove_all(d);
}

TEST(LoadMesh, BadFilesGiveOneLineErrors) {
    const fs::path d = tempDir();
    EXPECT_THROW(loadMesh((d / "missing.obj").string()), IoError);
    EXPECT_THROW(loadMesh((d / "mesh.xyz").string()), FormatError);
    writeText(d / "empty.obj", "");
    EXPECT_THROW(loadMesh((d / "empty.obj").string()), FormatError);
    writeText(d / "garbage.ply", "this is not a ply file\n\x01\x02\x03");
    EXPECT_THROW(loadMesh((d / "garbage.ply").string()), FormatError);
    writeText(d / "truncated.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n");
    try {
        const TriangleMesh m = loadMesh((d / "truncated.off").string());
        EXPECT_FALSE(validateMesh(m).usable()); // if parsed at all, it cannot be baked
    } catch (const FormatError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    fs::remove_all(d);
}

TEST(LoadPoints, ReadsTextAndPlyAndRejectsBadLines) {
    const fs::path d = tempDir();
    writeText(d / "p.txt", "# comment\n1 2 3\n\n  -4.5 5e-1 6\r\n");
    const auto p = loadPoints((d / "p.txt").string());
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[1], glm::vec3(-4.5f, 0.5f, 6.0f));
    writeText(d / "p.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                           "property float z\nend_header\n1 2 3\n4 5 6\n");
    EXPECT_EQ(loadPoints((d / "p.ply").string()).size(), 2u);
    writeText(d / "nan.txt", "1 2 3\nnan 0 0\n");
    try {
        loadPoints((d / "nan.txt").string());
        FAIL() << "NaN accepted";
    } catch (const FormatError& e) {
        EXPECT_NE(std::string(e.what()).find(":2:"), std::string::npos) << e.what();
    }
    writeText(d / "two.txt", "1 2\n3 4 5\n");
    EXPECT_THROW(loadPoints((d / "two.txt").string()), FormatError);
    writeText(d / "four.txt", "1 2 3 4\n");
    EXPECT_THROW(loadPoints((d / "four.txt").string()), FormatError);
    writeText(d / "words.txt", "x y z\n");
    EXPECT_THROW(loadPoints((d / "words.txt").string()), FormatError);
    EXPECT_THROW(loadPoints((d / "none.txt").string()), IoError);
    fs::remove_all(d);
}

TEST(LoadMesh, NonManifoldMeshesAreReadExactlyAsWritten) {
    // Two cubes on one edge, their corners shared by index: the edge carries
    // four triangles. A halfedge reader must split such vertices; these
    // readers keep the file's arrays.
    TriangleMesh touching = solids::boxesSharingAnEdge({0, 0, 0}, 1.0f).mesh;
    std::vector<std::uint32_t> firstAt(touching.positions.size());
    TriangleMesh shared;
    for (std::size_t i = 0; i < touching.positions.size(); ++i) {
        const auto same = std::find(shared.positions.begin(), shared.positions.end(), touching.positions[i]);
        firstAt[i] = std::uint32_t(same - shared.positions.begin());
        if (same == shared.positions.end()) shared.positions.push_back(touching.positions[i]);
    }
    for (const auto& t : touching.triangles) shared.triangles.push_back({firstAt[t.x], firstAt[t.y], firstAt[t.z]});
    ASSERT_EQ(shared.positions.size(), 14u); // two corners of the shared edge, once each
    // A fan of two cones meeting at one vertex (a non-manifold vertex) on top.
    const auto apex = std::uint32_t(shared.positions.size());
    shared.positions.push_back({0.5f, 0.5f, 3.0f});
    const auto base = std::uint32_t(shared.positions.size());
    for (float z : {2.0f, 4.0f})
        for (int k = 0; k < 3; ++k)
            shared.positions.push_back({0.5f + std::cos(2.1f * float(k)), 0.5f + std::sin(2.1f * float(k)), z});
    for (std::uint32_t c = 0; c < 2; ++c)
        for (std::uint32_t k = 0; k < 3; ++k) {
            const std::uint32_t a = base + 3 * c + k, b = base + 3 * c + (k + 1) % 3;
            shared.triangles.push_back(c == 0 ? glm::uvec3(apex, b, a) : glm::uvec3(apex, a, b));
        }
    shared.triangles.push_back({base, base + 1, base + 2});
    shared.triangles.push_back({base + 3, base + 5, base + 4});

    for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply}) {
        const std::string text = f == MeshFormat::Obj   ? objText(shared)
                                 : f == MeshFormat::Off ? offText(shared)
                                                        : plyText(shared, PlyEncoding::Little, false, false);
        const TriangleMesh m = parse(text, f);
        expectSameMesh(m, shared, "non-manifold");
        const MeshReport r = validateMesh(m);
        EXPECT_EQ(r.nonManifoldEdges, 1u);
        EXPECT_TRUE(r.closed()) << r.summary();
        EXPECT_TRUE(r.oriented()) << r.summary();
    }
}

TEST(LoadMesh, ObjReadsEveryReferenceFormAndSkipsWhatCarriesNoSurface) {
    const std::string obj = "# Meshlab-like\nmtllib cube.mtl\no thing\n"
                            "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0 0.1 0.2 0.3 1\n"
                            "vt 0 0\nvt 1 0\nvn 0 0 1\ng side\nusemtl red\ns off\n"
                            "f 1/1/1 2/2/1 3/1/1 4/2/1\n" // a quad, v/vt/vn
                            "f 1//1 3//1 2//1\n"          // v//vn
                            "f -4/1 -2/2 -3/1\n"          // relative, v/vt
                            "f 1 2 3 4 5\n"               // a pentagon, 5 defined below
                            "l 1 2\np 3\n"
                            "v +2 -0.5e1 .5  # a trailing comment\n";
    const TriangleMesh m = parse(obj, MeshFormat::Obj);
    ASSERT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(m.positions[4], glm::vec3(2, -5, 0.5f));
    const std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 2, 1}, {0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    EXPECT_EQ(m.triangles, expected);
    EXPECT_EQ(m.name, "test");
    // A UTF-8 byte order mark in front is no statement.
    EXPECT_EQ(parse("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::Obj).triangles.size(), 1u);
}

TEST(LoadMesh, DuplicateFacesAndIsolatedVerticesAreKeptAndReported) {
    TriangleMesh box = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    box.triangles.push_back(box.triangles[4]);
    box.positions.push_back({9, 9, 9});
    for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off}) {
        const TriangleMesh m = parse(f == MeshFormat::Obj ? objText(box) : offText(box), f);
        expectSameMesh(m, box, "untidy box");
        const MeshReport r = validateMesh(m);
        EXPECT_EQ(r.duplicateTriangles, 1u);
        EXPECT_EQ(r.isolatedVertices, 1u);
        EXPECT_NE(r.summary().find("1 duplicate triangle, 1 isolated vertex"), std::string::npos) << r.summary();
    }
}

TEST(LoadMesh, MixedPolygonsAreFannedInEveryFormat) {
    // A square pyramid under a pentagon roof, all faces in one file.
    const std::string off = "OFF\n# a comment line\n7 4 0\n"
                            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1  # apex\n2 0 0\n2 1 0\n"
                            "4 3 2 1 0 255 0 0\n" // a quad with a colour
                            "3 0 1 4\n"
                            "5 1 5 6 2 4 0.5 0.5 0.5 1\n"
                            "3 2 3 4\n";
    const TriangleMesh m = parse(off, MeshFormat::Off);
    const std::vector<glm::uvec3> expected = {{3, 2, 1}, {3, 1, 0}, {0, 1, 4}, {1, 5, 6}, {1, 6, 2}, {1, 2, 4}, {2, 3, 4}};
    EXPECT_EQ(m.triangles, expected);
    EXPECT_EQ(m.positions.size(), 7u);

    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 2\nproperty list uchar int vertex_index\nend_header\n"
                            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n4 0 1 2 3\n3 0 1 4\n";
    const std::vector<glm::uvec3> plyExpected = {{0, 1, 2}, {0, 2, 3}, {0, 1, 4}};
    EXPECT_EQ(parse(ply, MeshFormat::Ply).triangles, plyExpected);

    const std::string stl = "solid poly\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
                            "vertex 0 1 0\nendloop\nendfacet\nendsolid poly\n";
    const std::vector<glm::uvec3> stlExpected = {{0, 1, 2}, {0, 2, 3}};
    EXPECT_EQ(parse(stl, MeshFormat::Stl).triangles, stlExpected);
}

TEST(LoadMesh, PlyTwinsInEveryEncodingLoadIdentically) {
    const TriangleMesh source = testMesh();
    for (bool doubles : {false, true})
        for (bool wide : {false, true})
            for (PlyEncoding e : {PlyEncoding::Ascii, PlyEncoding::Little, PlyEncoding::Big}) {
                const TriangleMesh m = parse(plyText(source, e, doubles, wide), MeshFormat::Ply);
                expectSameMesh(m, source, (std::string(doubles ? "double" : "float") + (wide ? " wide" : "")).c_str());
            }
}

TEST(LoadMesh, StlTwinsLoadIdenticallyWithCornersWelded) {
    const TriangleMesh source = testMesh();
    const TriangleMesh ascii = parse(stlAscii(source), MeshFormat::Stl);
    const TriangleMesh binary = parse(stlBinary(source), MeshFormat::Stl);
    // A binary file whose header starts with "solid", as some exporters write.
    const TriangleMesh solidHeader = parse(stlBinary(source, "solid but binary"), MeshFormat::Stl);
    expectSameMesh(ascii, binary, "ascii vs binary");
    expectSameMesh(solidHeader, binary, "'solid' header");
    // Welding restores the sphere's shared corners, first appearance first.
    EXPECT_EQ(ascii.positions.size(), source.positions.size());
    EXPECT_EQ(ascii.triangles.size(), source.triangles.size());
    EXPECT_TRUE(validateMesh(ascii).oriented()) << validateMesh(ascii).summary();
    for (std::size_t t = 0; t < source.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ(ascii.positions[ascii.triangles[t][k]], source.positions[source.triangles[t][k]]);
    // +0 and -0 are one position.
    const std::string signedZero = "solid z\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                   "vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
                                   "vertex -0 0 -0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid z\n";
    EXPECT_EQ(parse(signedZero, MeshFormat::Stl).positions.size(), 3u);
}

TEST(LoadMesh, TruncatedFilesAreRefusedAtEveryLength) {
    const TriangleMesh tet = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}, ""};
    const std::pair<MeshFormat, std::string> files[] = {
        {MeshFormat::Ply, plyText(tet, PlyEncoding::Ascii, false, false)},
        {MeshFormat::Ply, plyText(tet, PlyEncoding::Little, true, true)},
        {MeshFormat::Ply, plyText(tet, PlyEncoding::Big, false, false)},
        {MeshFormat::Stl, stlAscii(tet)},
        {MeshFormat::Stl, stlBinary(tet)},
        {MeshFormat::Off, offText(tet)},
    };
    for (const auto& [format, whole] : files) {
        ASSERT_EQ(parse(whole, format).triangles.size(), 4u);
        // Every strict prefix is refused, but those that lack only blanks
        // after the last number, or the name after an ASCII STL's "endsolid".
        const std::size_t endsolid = whole.rfind("endsolid");
        const std::size_t complete = endsolid != std::string::npos && whole[0] == 's'
                                         ? endsolid + 8
                                         : whole.find_last_not_of(" \n") + 1;
        for (std::size_t n = 0; n < complete; ++n) {
            const std::string prefix = whole.substr(0, n);
            const std::string what = parseError(prefix, format);
            EXPECT_EQ(what.rfind("m:", 0), 0u) << "prefix of " << n << " bytes: " << what;
        }
    }
    // OBJ declares nothing, so a cut at a line end is a smaller mesh; a cut
    // inside a face or a vertex is an error on that line.
    // A face cut to fewer than 3 vertices is skipped and counted, as such faces are in whole files.
    EXPECT_EQ(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2", MeshFormat::Obj).skippedFaces, 1u);
    EXPECT_EQ(parseError("v 0 0 0\nv 1 0", MeshFormat::Obj), "m:2: a vertex needs 3 coordinates, this one has 2");
    EXPECT_EQ(parseError("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0", MeshFormat::Stl),
              "m:5: file ends inside a vertex (truncated?)");
    EXPECT_EQ(parseError("OFF\n4 1 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n", MeshFormat::Off),
              "m:5: file ends after 3 of 4 vertices");
}

TEST(LoadMesh, AbsurdDeclaredCountsAreRefusedBeforeAnythingIsAllocated) {
    EXPECT_EQ(parseError("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n0123456789ab",
                         MeshFormat::Ply),
              "m:3: element 'vertex' declares 4000000000 instances of at least 12 bytes each, 48000000000 bytes, more "
              "than the 12 bytes the file holds for them (12 after the header): truncated, or the count is wrong");
    // A later element: what is left once the elements before take their least is what it is compared with.
    EXPECT_EQ(parseError("ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 20\nproperty list uchar int vertex_indices\n"
                         "end_header\n0123456789ab0123",
                         MeshFormat::Ply),
              "m:7: element 'face' declares 20 instances of at least 1 byte each, 20 bytes, more than the 4 bytes "
              "the file holds for them (16 after the header, less 12 that the elements before take at least): "
              "truncated, or the count is wrong");
    EXPECT_NE(parseError("ply\nformat ascii 1.0\nelement face 1000000000000\nproperty list uchar int vertex_indices\n"
                         "end_header\n3 0 1 2\n",
                         MeshFormat::Ply)
                  .find("m:3: element 'face' declares 1000000000000 instances"),
              std::string::npos);
    EXPECT_EQ(parseError("ply\nformat ascii 1.0\nelement vertex 99999999999999999999\nend_header\n", MeshFormat::Ply),
              "m:3: element count '99999999999999999999' is out of range for an integer");
    EXPECT_EQ(parseError("ply\nformat ascii 1.0\nelement vertex 8000000000\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n", MeshFormat::Ply).substr(0, 4), "m:3:");
    // A list length of 2^32 - 1 in a 40-byte body.
    std::string list = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
    const std::size_t body = list.size();
    list += std::string(36, '\0');
    put(list, std::uint32_t(0xffffffffu), false);
    list += std::string(12, '\0');
    EXPECT_EQ(parseError(list, MeshFormat::Ply),
              "m: byte " + std::to_string(body + 36) + ": face 0: a list of 4294967295 items runs past the end of the file");
    EXPECT_EQ(parseError("OFF\n2000000000 2000000000 0\n0 0 0\n", MeshFormat::Off),
              "m:2: the header declares 2000000000 vertices and 2000000000 faces, more than the 6 bytes after it can "
              "hold");
    EXPECT_EQ(parseError("OFF\n-1 2 0\n", MeshFormat::Off), "m:2: count '-1' is negative");
    std::string stl(84, ' ');
    stl[80] = stl[81] = stl[82] = stl[83] = '\xff';
    EXPECT_EQ(parseError(stl + std::string(100, '\0'), MeshFormat::Stl),
              "m: byte 80: binary STL header declares 4294967295 triangles, which take 214748364834 bytes; the file "
              "has 184");
}

TEST(LoadMesh, NonFiniteAndHugeCoordinatesAreRefusedWithTheirPlace) {
    EXPECT_EQ(parseError("v 0 0 0\nv nan 0 0\n", MeshFormat::Obj), "m:2: coordinate 'nan' is not finite");
    EXPECT_EQ(parseError("v 0 -inf 0\n", MeshFormat::Obj), "m:1: coordinate '-inf' is not finite");
    EXPECT_EQ(parseError("v 0 0 1e39\n", MeshFormat::Obj), "m:1: coordinate '1e39' is out of range for a 32-bit float");
    EXPECT_EQ(parseError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 NaN\n3 0 1 2\n", MeshFormat::Off),
              "m:5: coordinate 'NaN' is not finite");
    EXPECT_EQ(parseError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n0 nan 0\n",
                         MeshFormat::Ply),
              "m:8: vertex 0: 'nan' is not finite");
    EXPECT_EQ(parseError("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 -4e40\n",
                         MeshFormat::Stl),
              "m:6: coordinate '-4e40' is out of range for a 32-bit float");
    // Binary: the byte where the value starts.
    std::string ply = "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
                      "property double z\nend_header\n";
    const std::size_t at = ply.size() + 8;
    put(ply, 1.0, true);
    put(ply, 1e300, true);
    put(ply, 1.0, true);
    EXPECT_EQ(parseError(ply, MeshFormat::Ply),
              "m: byte " + std::to_string(at) + ": vertex 0: coordinate y = 1e+300 is out of range for a 32-bit float");
    TriangleMesh tri = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, ""};
    tri.positions[2].z = std::nanf("");
    EXPECT_EQ(parseError(stlBinary(tri), MeshFormat::Stl), "m: byte 120: triangle 0, corner 2 is not finite");
    // Large but finite coordinates, and tiny ones that round to zero, are numbers like any other.
    const TriangleMesh big = parse("v 3e38 -3e38 1e-50\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::Obj);
    EXPECT_EQ(big.positions[0], glm::vec3(3e38f, -3e38f, 0.0f));
}

TEST(LoadMesh, MalformedFilesNameTheLineOrByte) {
    struct Case {
        MeshFormat format;
        std::string text;
        std::string error;
    };
    const Case table[] = {
        {MeshFormat::Obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "m:4: vertex reference 0: OBJ counts vertices from 1"},
        {MeshFormat::Obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\nf 1 2 3\n",
         "m:4: vertex 9 does not exist (the file has 3 vertices)"},
        {MeshFormat::Obj, "v 0 0 0\nf -1 -2 -3\n", "m:2: vertex reference -2 points before the first vertex (1 read so far)"},
        {MeshFormat::Obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/4/5/6\n",
         "m:4: vertex reference '3/4/5/6' is not v, v/vt, v//vn or v/vt/vn"},
        {MeshFormat::Obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "m:4: vertex reference 'x' is not an integer"},
        {MeshFormat::Obj, "v 1 2 three\n", "m:1: coordinate 'three' is not a 32-bit float"},
        {MeshFormat::Obj, "v 1 2 3 4 5 6 7 8\n", "m:1: a vertex has at most 7 numbers, this one has 8"},
        {MeshFormat::Obj, "cstype bspline\n", "m:1: free-form geometry ('cstype') is not supported; only polygons are read"},
        {MeshFormat::Obj, "v 0 0 0\n\x01\x02 garbage\n", "m:2: '\\x01\\x02' is not an OBJ statement"},
        {MeshFormat::Off, "COFF\n3 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2 1 2 3 4 5\n",
         "m:6: the face has 5 numbers after its 3 vertices (a colour has at most 4)"},
        {MeshFormat::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
         "m:6: vertex index 3 is out of range (the file has 3 vertices, numbered from 0)"},
        {MeshFormat::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "m:6: the face declares 4 vertices, the line holds 3 more numbers"},
        {MeshFormat::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
         "m:7: more data after the 3 vertices and 1 faces the header declares"},
        {MeshFormat::Off, "4OFF\n1 0 0\n0 0 0 1\n", "m:1: '4OFF': only 3-dimensional OFF is supported"},
        {MeshFormat::Off, "nOFF8 6 12\n", "m:1: 'nOFF': only 3-dimensional OFF is supported"},
        {MeshFormat::Off, "XOFF\n", "m:1: 'XOFF' is not an OFF header ([ST][C][N]OFF)"},
        {MeshFormat::Off, "OFFICE 1 2\n", "m:1: not an OFF file (the first line is not 'OFF' or a variant such as 'COFF')"},
        {MeshFormat::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-1 0\n", "m:6: face size -1 is negative"},
        {MeshFormat::Off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 3\n",
         "m:6: vertex index 3 is out of range (the file has 3 vertices, numbered from 0)"},
        {MeshFormat::Obj, "v 0 0 0\nv 1 0 0\nf 1 3\n", "m:3: vertex 3 does not exist (the file has 2 vertices)"},
        {MeshFormat::Obj, "v 0 0 0\\x\n", "m:1: coordinate '0\\x' is not a 32-bit float"},
        {MeshFormat::Obj, "v 0 0 0 red 1 1\n", "m:1: vertex attribute 'red' is not a number"},
        {MeshFormat::Obj, "v 0 \\\n nan 0 1 1 1\n", "m:2: coordinate 'nan' is not finite"},
        {MeshFormat::Off, "OFF BINARY\n", "m:1: binary OFF is not supported"},
        {MeshFormat::Off, "PLY\n", "m:1: not an OFF file (the first line is not 'OFF' or a variant such as 'COFF')"},
        {MeshFormat::Ply, "solid x\n", "m:1: not a PLY file (no 'ply' line first)"},
        {MeshFormat::Ply, "ply\nelement vertex 0\nend_header\n", "m:3: the header has no format line"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float32 x\nproperty half y\n",
         "m:5: 'half' is not a PLY type"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n",
         "m:4: a list's count type must be an integer type"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n3 0 1 2\n",
         "m:3: vertex indices must be of an integer type"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
         "m:3: the vertex element needs scalar properties x, y and z"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement face 1\nproperty uchar n\nend_header\n3\n",
         "m:3: the face element needs a list property vertex_indices"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n3 0 1 2\n",
         "m:3: triangle strips ('tristrips') are not supported"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
         "m:13: face 0: vertex index 3 is out of range (3 vertices)"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 5\n",
         "m:13: face 0: vertex index 5 is out of range (3 vertices)"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 1\nproperty uchar x\nproperty float y\nproperty float z\n"
                          "end_header\n256 0 0\n",
         "m:8: '256' is out of range for uchar"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                          "end_header\n0 0 0\n1 1 1\n",
         "m:9: data after the last element the header declares"},
        {MeshFormat::Ply, "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar x\n"
                          "property uchar y\nproperty uchar z\nend_header\n\x01\x02\x03\x04",
         "m: byte 118: 1 byte after the last element the header declares"},
        {MeshFormat::Ply, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "m:4: the header has no end_header line (truncated, or not a PLY file)"},
        {MeshFormat::Stl, "solid s\nfacet 0 0 1\n", "m:2: expected 'normal', found '0'"},
        {MeshFormat::Stl, "solid s\nendsolid s\nfacet\n", "m:3: expected 'solid' or the end of the file, found 'facet'"},
        {MeshFormat::Stl, "not an stl", "m: not an STL file: not ASCII (no 'solid' first) and shorter than the 84 bytes of a binary header"},
    };
    for (const Case& c : table) EXPECT_EQ(parseError(c.text, c.format), c.error) << c.text;
}

TEST(LoadMesh, CrashesOfTheFormerReaderAreOneLineErrors) {
    // The three files of the bug report, byte for byte: an OBJ that aborted
    // OpenMesh's reader (assertion in OBJReader.cc), a PLY that crashed it
    // and a PLY on which it hung.
    const std::string abortObj(
        "# cubo cube\n"
        "v 1 0 0\n"
        "v 100 0\n"
        "v 1 1 0\n"
        "v 0 1 0\n"
        "v 0 0 1\n"
        "v 1 0 1\n"
        "v 1 1 1\n"
        "f 1/1/1 4/2/1 3/3/1 2/1/1\n"
        "f 5//1 6//1 7//1 8//18 -7 -3 -4\n"
        "f 2 3 \xc1 6\n"
        "f 1 3/3/1 2/1/1\n"
        "f 5/ 0 1 0\n"
        "v 0 0 1\n"
        "v 1 0 1\n"
        "v 1 1 1\n"
        "f /1 6//1 7//1 8//18 -7 -3 -4\n"
        "f 2 3 \xc1 6\n"
        "f 1 4 8 7\n"
        "f 4\n"
        "f 4 1 5 8\n");
    const char segv[] =
        "ply\n"
        "format binary_little_endian 1.0\n"
        "eleeent vertex 4\n"
        "property float x\n"
        "pdiffuseg_reat y\n"
        "property float z\n"
        "element face 4\n"
        "property %ist uchar int vertex_indices\n"
        "end_header\n"
        "\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\xba\x80?\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00"
        "\x00\x00\x80?\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80?\x03\x00\x00\x00\x00\x02\x00\x00\x00"
        "\x01\x00\x00\x00\x03\x00\x00\x00\x00\x01\x00\x00\x00\x03\x00\x00\x00\x03\x00\x00\x00\x00\x03\x00\x00\x00\x02"
        "\x00\x00\x00\x03\x01\x00\x00\x00\x02\x00\x00\x00\x03\x00\x00\x00";
    const char hang[] =
        "ply\n"
        "format binary_little_endian ex 4\n"
        "properloat z\n"
        "element face 8\n"
        "property list uchar int vertex_indices\n"
        "end_header\n"
        "\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80?\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00"
        "\x00\x00\x80?\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x80?\x03\x00\x00\x00\x00\x02\x00\x00\x00"
        "\x01\x00\x00\x00\x03\x00\x00\x00\x00\x01\x00\x00\x00\x03\x00\x00\x00\x03\x00\x00\x00\x00\x03\x00\x00\x00\x02"
        "\x00\x00\x00\x03\x01\x00\x00\x00\x02\x00\x00\x00\x03\x00\x00\x00";
    ASSERT_EQ(abortObj.size(), 251u);
    ASSERT_EQ(sizeof segv - 1, 269u);
    ASSERT_EQ(sizeof hang - 1, 215u);
    EXPECT_EQ(parseError(abortObj, MeshFormat::Obj), "m:3: a vertex needs 3 coordinates, this one has 2");
    EXPECT_EQ(parseError(std::string(segv, sizeof segv - 1), MeshFormat::Ply), "m:3: 'eleeent' is not a PLY header keyword");
    EXPECT_EQ(parseError(std::string(hang, sizeof hang - 1), MeshFormat::Ply),
              "m:2: expected 'format binary_little_endian 1.0'");
    // Repaired where they first go wrong, they fail further on, still in one line.
    std::string obj = abortObj;
    obj.replace(obj.find("v 100 0"), 7, "v 1 0 0");
    EXPECT_EQ(parseError(obj, MeshFormat::Obj), "m:11: vertex reference '\\xc1' is not an integer");
}

TEST(LoadMesh, BinaryPlyOfTheCommonLayoutIsCheckedAsStrictly) {
    // Float vertices and uchar/int face lists, little-endian: the layout
    // read by the tight loops; their problems are named as in any layout.
    const auto file = [](float y1, std::int32_t lastIndex) {
        std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
        const float xyz[9] = {0, 0, 0, 1, y1, 0, 0, 1, 0};
        for (float v : xyz) put(s, v, false);
        put(s, std::uint8_t(3), false);
        for (std::int32_t i : {0, 1, 2}) put(s, i, false);
        put(s, std::uint8_t(3), false);
        for (std::int32_t i : {2, 1, lastIndex}) put(s, i, false);
        return s;
    };
    const std::size_t header = file(0, 0).size() - 36 - 2 * 13;
    const TriangleMesh m = parse(file(0.5f, 0), MeshFormat::Ply);
    EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0.5f, 0}, {0, 1, 0}}));
    EXPECT_EQ(m.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {2, 1, 0}}));
    EXPECT_EQ(parseError(file(0, 3), MeshFormat::Ply),
              "m: byte " + std::to_string(header + 36 + 13 + 9) + ": face 1: vertex index 3 is out of range (3 vertices)");
    EXPECT_EQ(parseError(file(0, -1), MeshFormat::Ply),
              "m: byte " + std::to_string(header + 36 + 13 + 9) + ": face 1: vertex index -1 is out of range (3 vertices)");
    EXPECT_EQ(parseError(file(INFINITY, 0), MeshFormat::Ply),
              "m: byte " + std::to_string(header + 16) + ": vertex 1: coordinate y = inf is not finite");
    std::string cut = file(0, 0);
    cut.pop_back();
    EXPECT_EQ(parseError(cut, MeshFormat::Ply).substr(0, 7), "m: byte");
}

TEST(LoadMesh, AsciiPlyLinesMayHoldMoreThanTheirElementDeclares) {
    // As a common writer (VCG, behind MeshLab) lays out faces with texture
    // coordinates: one element per line, and more numbers on a face's line
    // than its header declares. Laid out one per line, the extra numbers up
    // to the line's end are read past; they must still be numbers.
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nproperty uchar red\nelement face 4\n"
                               "property list uchar int vertex_indices\nproperty list uchar float texcoord\n"
                               "property uchar red\nend_header\n";
    const std::string vertices = "0 0 0 192 \n1 0 0 192\n0 1 0 192\n0 0 1 192\n";
    const std::string faces = "3 0 2 1 6 0.5 0.5 0.5 0.5 0.5 0.5 9 1 1 1 1 1\n3 0 1 3 6 0 0 0 0 0 0 9 1 1\n"
                              "3 0 3 2 2 0 0 9\n3 1 2 3 6 0 0 0 0 0 0 9 1 1 1 1 1 1 1 1 1 \n";
    const TriangleMesh m = parse(header + vertices + faces, MeshFormat::Ply);
    EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
    EXPECT_EQ(m.triangles, (std::vector<glm::uvec3>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
    std::string bad = header + vertices + faces;
    bad.replace(bad.find("9 1 1\n"), 6, "9 1 x\n");
    EXPECT_EQ(parseError(bad, MeshFormat::Ply), "m:18: 'x' is not a number");
    // Not laid out one per line (the first vertex does not fill its line):
    // tokens are read in sequence, and the extra numbers leave data over.
    EXPECT_EQ(parseError(header + "0 0 0 192 1 0 0 192\n0 1 0 192\n0 0 1 192\n" + faces, MeshFormat::Ply),
              "m:18: data after the last element the header declares");
}

TEST(LoadMesh, ObjLineContinuationsJoinAStatementWithTheNextLine) {
    // A `\` ending a line (LF or CRLF) continues the statement, or the
    // comment; errors name the physical line they are on.
    const TriangleMesh m = parse("v 0 0 \\\n0\nv 1 \\\r\n 0 0\r\nv 0 1 0 \\\n\nf 1 \\\n 2 \\\n 3\n# done \\\nv 9 9 9\n# \\x\n",
                                 MeshFormat::Obj);
    EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    EXPECT_EQ(m.triangles, (std::vector<glm::uvec3>{{0, 1, 2}}));
    EXPECT_EQ(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 \\", MeshFormat::Obj).triangles.size(), 1u);
    EXPECT_EQ(parseError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n2 \\\n 0\n", MeshFormat::Obj),
              "m:6: vertex reference 0: OBJ counts vertices from 1");
    EXPECT_EQ(parseError("v 0 0 \\\n\\\n", MeshFormat::Obj), "m:3: a vertex needs 3 coordinates, this one has 2");
}

TEST(LoadMesh, NumbersBesidePositionsMayBeNonFiniteOrMany) {
    // Vertex colours (some exporters write NaN for "none"), w, texture
    // coordinates and normals carry no position: read past, whatever their
    // value. Positions stay strict (MalformedFilesNameTheLineOrByte).
    const TriangleMesh obj = parse("v 0 0 0 nan nan nan\nv 1 0 0 1 0.5 0 1\nv 0 1 0 -inf 0 inf\nvt nan nan\n"
                                   "vn nan 0 inf\nvt 0.5 0.5 0.5\nf 1/1/1 2/2/1 3//1\n",
                                   MeshFormat::Obj);
    EXPECT_EQ(obj.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    EXPECT_EQ(obj.triangles, (std::vector<glm::uvec3>{{0, 1, 2}}));
    const TriangleMesh off = parse("COFF\n3 1 0\n0 0 0 nan nan nan 1\n1 0 0 1 1 1 1\n0 1 0 1 inf 1 1\n3 0 1 2 nan 0 0 1\n",
                                   MeshFormat::Off);
    EXPECT_EQ(off.positions, obj.positions);
    EXPECT_EQ(off.triangles, obj.triangles);
    const TriangleMesh ply = parse("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                   "property float z\nproperty float red\nend_header\n0 0 0 nan\n1 0 0 inf\n0 1 0 1\n",
                                   MeshFormat::Ply);
    EXPECT_EQ(ply.positions, obj.positions);
}

TEST(LoadMesh, FacesOfFewerThanThreeVerticesAreSkippedAndCounted) {
    // The tetrahedron, with faces of 2, 1 and 0 vertices among its triangles
    // (exporters write such faces for lines and points): the triangles load,
    // the others are counted, and validation names them.
    const TriangleMesh tet = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}, ""};
    const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    const std::string obj = "v " + std::string("0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n") +
                            "f 1 3 2\nf 1 2\nf 1 2 4\nf 4\nf 1 4 3\nf\nf 2 3 4\n";
    const std::string off = "OFF\n4 7 0\n" + vertices + "3 0 2 1\n2 0 1\n3 0 1 3\n1 3\n3 0 3 2\n0\n3 1 2 3\n";
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 7\nproperty list uchar int vertex_indices\nend_header\n" +
                            vertices + "3 0 2 1\n2 0 1\n3 0 1 3\n1 3\n3 0 3 2\n0\n3 1 2 3\n";
    std::string plyBinary = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n";
    for (const glm::vec3& p : tet.positions)
        for (int k = 0; k < 3; ++k) put(plyBinary, p[k], false);
    const std::vector<std::vector<int>> faces = {{0, 2, 1}, {0, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& f : faces) {
        put(plyBinary, std::uint8_t(f.size()), false);
        for (int i : f) put(plyBinary, std::int32_t(i), false);
    }
    std::string stl = stlAscii(tet);
    stl.insert(stl.find("facet"), "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n");
    const std::tuple<MeshFormat, std::string, std::size_t> files[] = {
        {MeshFormat::Obj, obj, 3}, {MeshFormat::Off, off, 3}, {MeshFormat::Ply, ply, 3},
        {MeshFormat::Ply, plyBinary, 1}, {MeshFormat::Stl, stl, 1}};
    for (const auto& [format, text, skipped] : files) {
        const TriangleMesh m = parse(text, format);
        if (format != MeshFormat::Stl) expectSameMesh(m, tet, text.c_str());
        EXPECT_EQ(m.triangles.size(), 4u) << text;
        EXPECT_EQ(m.skippedFaces, skipped) << text;
        const MeshReport r = validateMesh(m);
        EXPECT_TRUE(r.oriented()) << r.summary();
        EXPECT_EQ(r.skippedFaces, skipped);
        EXPECT_NE(r.summary().find(", " + std::to_string(skipped) + (skipped == 1 ? " face" : " faces") +
                                   " of fewer than 3 vertices skipped"),
                  std::string::npos)
            << r.summary();
    }
}

TEST(LoadMesh, OffHeadersAsExportersWriteThem) {
    // The tetrahedron's vertices and faces after each header.
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string withColours = "0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n0 0 1 1 1 1 1\n"
                                    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string withNormals = "0 0 0 -1 -1 -1\n1 0 0 1 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n"
                                    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string withTexture = "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n0 0 1 1 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string headers[] = {
        "OFF\n4 4 6\n" + body,
        "OFF 4 4 6\n" + body,
        "\t      OFF4 4 6 # counts right after the keyword, blanks in front\n" + body,
        "# a comment first\n\nOFF\n# and after the header\n\n4 4 6\n" + body,
        "OFF\r\n4 4\r\n" + body,
        "COFF\n4 4 6\n" + withColours,
        "NOFF\n4 4 6\n" + withNormals,
        "STOFF\n4 4 6\n" + withTexture,
        "CNOFF 4 4 6\n0 0 0 -1 -1 -1 1 0 0 1\n1 0 0 1 0 0 0 1 0 1\n0 1 0 0 1 0 0 0 1 1\n0 0 1 0 0 1 1 1 1 1\n"
        "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
    };
    for (const std::string& text : headers) {
        const TriangleMesh m = parse(text, MeshFormat::Off);
        EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}})) << text;
        EXPECT_EQ(m.triangles.size(), 4u) << text;
        EXPECT_TRUE(validateMesh(m).oriented()) << text;
    }
}

TEST(LoadMesh, EmptyFilesAndDirectoriesAreRefused) {
    const fs::path d = tempDir();
    for (const char* name : {"empty.obj", "empty.ply", "empty.stl", "empty.off"}) {
        writeText(d / name, "");
        EXPECT_EQ(formatError([&] { loadMesh((d / name).string()); }), (d / name).string() + ": file is empty");
    }
    fs::create_directories(d / "folder.obj");
    try {
        loadMesh((d / "folder.obj").string());
        ADD_FAILURE() << "a directory was read";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()), (d / "folder.obj").string() + ": cannot read: is a directory");
    }
    EXPECT_THROW(loadPoints((d / "folder.obj").string()), IoError);
    // An OBJ of comments only is a mesh with nothing in it, which validation names.
    EXPECT_EQ(validateMesh(parse("# nothing\n\n", MeshFormat::Obj)).summary(), "empty: no triangles");
    fs::remove_all(d);
}

TEST(LoadMesh, FormatsAreChosenByExtensionInAnyCase) {
    EXPECT_EQ(meshFormatOf("a/b.OBJ"), MeshFormat::Obj);
    EXPECT_EQ(meshFormatOf("b.Ply"), MeshFormat::Ply);
    EXPECT_EQ(meshFormatOf("b.stl"), MeshFormat::Stl);
    EXPECT_EQ(meshFormatOf("b.off"), MeshFormat::Off);
    EXPECT_EQ(formatError([] { meshFormatOf("mesh.3ds"); }),
              "mesh.3ds: unsupported mesh format '.3ds' (expected .obj, .ply, .stl or .off)");
}

TEST(LoadPoints, PlyPointsInEveryEncodingAndTextAgree) {
    const TriangleMesh source = testMesh();
    std::string text = "# points\n";
    for (const auto& v : source.positions) text += num(v.x) + " " + num(v.y) + " " + num(v.z) + "\n";
    EXPECT_EQ(parsePoints(text.data(), text.size(), PointFormat::Text, "p"), source.positions);
    for (PlyEncoding e : {PlyEncoding::Ascii, PlyEncoding::Little, PlyEncoding::Big}) {
        const std::string ply = plyText(source, e, true, false);
        EXPECT_EQ(parsePoints(ply.data(), ply.size(), PointFormat::Ply, "p"), source.positions);
    }
    const std::string binary = std::string("1 2 3\n\0", 7);
    EXPECT_EQ(formatError([&] { parsePoints(binary.data(), binary.size(), PointFormat::Text, "p"); }),
              "p: not a text file of 'x y z' lines (it holds NUL bytes)");
    EXPECT_EQ(formatError([] { parsePoints("1 2 3\n4 5 1e39\n", 15, PointFormat::Text, "p"); }),
              "p:2: coordinate '1e39' is out of range for a 32-bit float");
}

} // namespace
} // namespace vds
