// Mesh validation, on meshes built in code.
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <vds/error.h>
#include <vds/exact.h>
#include <vds/bake.h>
#include <vds/detail/edge_partners.h>
#include <vds/mesh.h>
#include <vds/mesh_check.h>
#include <vds/sprite.h>
#include "solids.h"

#include "points.h"

namespace vds {
namespace {

TEST(ValidateMesh, GeneratedSolidsAreClosed) {
    for (const auto& s : {solids::box({0, 0, 0}, {1, 1, 1}), solids::sphere({0, 0, 0}, 1, 32),
                          solids::torus({0, 0, 0}, 1, 0.3f, 32), solids::shell({0, 0, 0}, 1, 0.5f, 32),
                          solids::overlappingBoxes({0, 0, 0}, {1, 1, 1}, {0.5f, 0.5f, 0.5f}, {2, 2, 2})}) {
        const MeshReport r = validateMesh(s.mesh);
        EXPECT_TRUE(r.closed()) << s.mesh.name << ": " << r.summary();
        EXPECT_TRUE(r.usable());
        EXPECT_EQ(r.degenerateTriangles, 0u) << s.mesh.name;
    }
}

// The benchmark's trefoil: closed, facing out (positive volume, about the
// tube's cross-section times the centre line's length), inside along its
// centre line and outside away from the tube.
TEST(ValidateMesh, TorusKnotIsAClosedTubeFacingOut) {
    const auto knot = solids::torusKnot({0.5f, -0.5f, 0.25f}, 2.0f, 2, 3, 0.2f, 300, 24);
    EXPECT_EQ(knot.mesh.triangles.size(), 2u * 300u * 24u);
    const MeshReport r = validateMesh(knot.mesh);
    EXPECT_TRUE(r.closed()) << r.summary();
    EXPECT_EQ(r.degenerateTriangles, 0u);
    double volume = 0.0, length = 0.0;
    for (const auto& t : knot.mesh.triangles) {
        const glm::dvec3 a(knot.mesh.positions[t.x]), b(knot.mesh.positions[t.y]), c(knot.mesh.positions[t.z]);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    for (std::size_t i = 0; i < knot.line.size(); ++i)
        length += glm::length(glm::dvec3(knot.line[(i + 1) % knot.line.size()] - knot.line[i]));
    const double tube = 3.14159265358979 * 0.2 * 0.2 * length;
    EXPECT_NEAR(volume, tube, 0.03 * tube);
    const ExactClassifier exact(knot.mesh);
    for (std::size_t i = 0; i < knot.line.size(); i += 7) {
        EXPECT_TRUE(exact.contains(knot.line[i])) << "centre line point " << i;
        EXPECT_LT(knot.distance(knot.line[i]), -0.19f);
    }
    const auto points = test::randomPoints(r.bounds, 3000, 0.1f, 4);
    std::size_t far = 0;
    for (const auto& p : points) {
        const float d = knot.distance(p);
        if (std::fabs(d) < 0.05f) continue;
        ++far;
        EXPECT_EQ(exact.contains(p), d < 0.0f) << "distance " << d;
    }
    EXPECT_GT(far, 2000u);
}

TEST(ValidateMesh, FindsBoundaryNonManifoldFlippedAndDegenerateFaces) {
    auto open = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    open.triangles.pop_back();
    MeshReport r = validateMesh(open);
    EXPECT_EQ(r.boundaryEdges, 3u);
    EXPECT_FALSE(r.closed());
    EXPECT_NE(r.summary().find("3 boundary edges"), std::string::npos) << r.summary();

    auto fin = solids::box({0, 0, 0}, {1, 1, 1}).mesh; // a fin: a third triangle on an existing edge
    fin.positions.push_back({0.5f, -1.0f, 0.0f});
    fin.triangles.push_back({0, 1, std::uint32_t(fin.positions.size() - 1)});
    r = validateMesh(fin);
    EXPECT_EQ(r.nonManifoldEdges, 1u);
    EXPECT_EQ(r.oddNonManifoldEdges, 1u);
    EXPECT_EQ(r.boundaryEdges, 2u);

    auto flipped = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
    r = validateMesh(flipped);
    EXPECT_GT(r.inconsistentEdges, 0u);

    auto degenerate = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    degenerate.triangles.push_back({0, 0, 1});
    r = validateMesh(degenerate);
    EXPECT_EQ(r.degenerateTriangles, 1u);
    EXPECT_TRUE(r.closed()); // a collapsed triangle adds no edges
}

TEST(ValidateMesh, SolidsTouchingAlongAnEdgeAreClosedButNotManifold) {
    const auto boxes = solids::boxesSharingAnEdge({0, 0, 0}, 1.0f);
    const MeshReport r = validateMesh(boxes.mesh);
    EXPECT_EQ(r.nonManifoldEdges, 1u);
    EXPECT_EQ(r.oddNonManifoldEdges, 0u);
    EXPECT_EQ(r.boundaryEdges, 0u);
    EXPECT_EQ(r.inconsistentEdges, 0u);
    EXPECT_TRUE(r.closed());
    EXPECT_TRUE(r.oriented());
    EXPECT_FALSE(r.manifold());
    EXPECT_EQ(r.summary(), "closed, 1 non-manifold edge, 24 triangles, 16 vertices");
    EXPECT_NO_THROW(requireInsideDefined(r, "boxes.obj", Rule::Parity));
    EXPECT_NO_THROW(requireInsideDefined(r, "boxes.obj", Rule::Winding));
    // Inside is defined: a note, not a warning.
    EXPECT_EQ(insideWarning(r, Rule::Parity), "");
    EXPECT_EQ(insideNote(r, Rule::Parity),
              "1 non-manifold edge (more than two triangles on an edge); inside is still defined by the parity rule");
    EXPECT_EQ(insideNote(validateMesh(solids::box({0, 0, 0}, {1, 1, 1}).mesh), Rule::Parity), "");
    EXPECT_EQ(insideWarning(validateMesh(solids::box({0, 0, 0}, {1, 1, 1}).mesh), Rule::Winding), "");
}

TEST(ValidateMesh, AnEdgeOfThreeTrianglesLeavesInsideUndefined) {
    // Two boxes sharing a wall that is there once: its four edges carry three
    // triangles each, so a ray's parity changes across them as across a hole.
    const auto a = solids::box({0, 0, 0}, {1, 1, 1}).mesh, b = solids::box({1, 0, 0}, {2, 1, 1}).mesh;
    TriangleMesh theta = a; // a whole, the shared wall (a's x = 1 side, triangles 10 and 11) included
    auto withoutLowXSide = b;
    withoutLowXSide.triangles.erase(withoutLowXSide.triangles.begin() + 8, withoutLowXSide.triangles.begin() + 10);
    theta = solids::merge(theta, withoutLowXSide);
    theta.triangles.erase(theta.triangles.begin() + 10, theta.triangles.begin() + 12);
    theta.triangles.push_back(a.triangles[10]);
    theta.triangles.push_back(a.triangles[11]);
    const MeshReport r = validateMesh(theta);
    EXPECT_EQ(r.boundaryEdges, 0u);
    EXPECT_EQ(r.nonManifoldEdges, 4u);
    EXPECT_EQ(r.oddNonManifoldEdges, 4u);
    EXPECT_FALSE(r.closed());
    EXPECT_NE(r.summary().find("open (4 edges shared by an odd number of triangles; 4 edges in the generalized "
                               "winding number's boundary)"),
              std::string::npos)
        << r.summary();
    EXPECT_THROW(requireInsideDefined(r, "theta.obj", Rule::Parity), InvalidMesh);
}

TEST(ValidateMesh, CountsDuplicateTrianglesIsolatedVerticesAndOrientationConflicts) {
    auto m = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    m.triangles.push_back(m.triangles[0]);                                                // same orientation
    m.triangles.push_back({m.triangles[1].x, m.triangles[1].z, m.triangles[1].y});       // reversed
    m.positions.push_back({5, 5, 5});                                                     // used by nothing
    m.positions.push_back(m.positions[0]);                                                // unused, but its twin is used
    const MeshReport r = validateMesh(m);
    EXPECT_EQ(r.duplicateTriangles, 2u);
    EXPECT_EQ(r.isolatedVertices, 1u);
    EXPECT_EQ(r.vertexCount, 10u);
    EXPECT_NE(r.summary().find("2 duplicate triangles, 1 isolated vertex"), std::string::npos) << r.summary();

    auto flipped = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
    const MeshReport f = validateMesh(flipped);
    EXPECT_EQ(f.inconsistentEdges, 3u);
    EXPECT_TRUE(f.closed());
    EXPECT_FALSE(f.oriented());
    EXPECT_TRUE(f.misoriented());
    EXPECT_EQ(f.windingBoundaryEdges, 6u); // each conflicting edge used twice the same way
    EXPECT_STREQ(f.status(), "mis-oriented");
    EXPECT_EQ(f.summary(), "closed but mis-oriented (3 inconsistently oriented edges; 6 edges in the generalized "
                           "winding number's boundary), 12 triangles, 8 vertices");
    EXPECT_NO_THROW(requireInsideDefined(f, "flipped.obj", Rule::Parity));
    EXPECT_EQ(insideWarning(f, Rule::Parity), misorientedMessage(f, "the mesh"));
    const MeshFlags cli{"--rule generalized-winding", ""}; // the vds tool's spelling
    try {
        requireInsideDefined(f, "flipped.obj", Rule::Winding, cli);
        FAIL() << "winding accepted with orientation conflicts";
    } catch (const InvalidMesh& e) {
        EXPECT_STREQ(e.what(), "flipped.obj has 3 inconsistently oriented edges: inside is not defined by the "
                               "winding rule; the parity rule and the generalized winding number (--rule "
                               "generalized-winding) answer for it");
        EXPECT_EQ(openMeshMessage(f, "flipped.obj", Rule::Winding, cli), e.what()); // one wording, one place
    }
}

// A flat sheet bounds no volume: one message, naming the flat axes, wherever a volume is needed.
TEST(ValidateMesh, FlatMeshesGetOneMessage) {
    TriangleMesh sheet;
    sheet.positions = {{0, 0, 2}, {1, 0, 2}, {0, 1, 2}, {1, 1, 2}};
    sheet.triangles = {{0, 1, 2}, {2, 1, 3}};
    const MeshReport report = validateMesh(sheet);
    EXPECT_TRUE(report.flat());
    EXPECT_FALSE(validateMesh(solids::box({0, 0, 0}, {1, 1, 1}).mesh).flat());
    const std::string expected = "sheet.obj is flat (no extent along z): it bounds no volume, so no point is inside "
                                 "it by any rule and nothing is baked or written; its generalized winding number "
                                 "still measures points off the sheet (between -1/2 and 1/2)";
    try {
        requireVolume(report, "sheet.obj");
        FAIL() << "flat mesh accepted";
    } catch (const InvalidMesh& e) {
        EXPECT_EQ(e.what(), expected);
    }
    BakeOptions o;
    o.resolution = 16;
    o.sourceName = "sheet.obj";
    for (std::optional<Axis> axis : {std::optional<Axis>(), std::optional<Axis>(Axis::X)}) {
        o.axis = axis;
        try {
            bakeCpu(sheet, o);
            FAIL() << "flat mesh baked";
        } catch (const InvalidMesh& e) {
            EXPECT_EQ(e.what(), expected);
        }
    }
}

TEST(ValidateMesh, OpenMeshesHaveNoInsideAndTheMessageSaysWhatAnswers) {
    auto open = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    open.triangles.pop_back();
    EXPECT_NO_THROW(requireInsideDefined(validateMesh(open), "open.obj", Rule::GeneralizedWinding));
    const MeshFlags cli{"--rule generalized-winding", ""}; // the vds tool's spelling
    for (Rule rule : {Rule::Parity, Rule::Winding}) {
        try {
            requireInsideDefined(validateMesh(open), "open.obj", rule, cli);
            FAIL() << "open mesh accepted";
        } catch (const InvalidMesh& e) {
            const std::string expected = std::string("open.obj is open (3 boundary edges): inside is not defined "
                                                     "by the ") +
                                         toString(rule) +
                                         " rule; the generalized winding number answers for it (--rule "
                                         "generalized-winding)";
            EXPECT_EQ(std::string(e.what()), expected);
            EXPECT_EQ(openMeshMessage(validateMesh(open), "open.obj", rule, cli), e.what());
            // A flag is named only by a caller that has it.
            EXPECT_EQ(openMeshMessage(validateMesh(open), "open.obj", rule, {"--rule generalized-winding", "--allow-open"}),
                      expected + ", and answering anyway (--allow-open) counts crossings as for a surface, not a solid");
            // The library's own default names no flag of any caller.
            EXPECT_EQ(openMeshMessage(validateMesh(open), "open.obj", rule),
                      std::string("open.obj is open (3 boundary edges): inside is not defined by the ") +
                          toString(rule) + " rule; the generalized winding number answers for it");
        }
    }
    EXPECT_THROW(requireInsideDefined(validateMesh(TriangleMesh{}), "empty.obj", Rule::Parity), InvalidMesh);
}

TEST(ValidateMesh, DuplicatedVerticesAreWeldedByPosition) {
    TriangleMesh soup; // the box as a triangle soup: every triangle has its own vertices
    const auto box = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    for (const auto& t : box.triangles) {
        const auto base = std::uint32_t(soup.positions.size());
        for (int k = 0; k < 3; ++k) soup.positions.push_back(box.positions[t[k]]);
        soup.triangles.push_back({base, base + 1, base + 2});
    }
    EXPECT_TRUE(validateMesh(soup).closed());
}

TEST(ValidateMesh, UnusableMeshesAreRefused) {
    EXPECT_THROW(requireUsable(validateMesh(TriangleMesh{}), "empty.obj"), InvalidMesh);
    auto nan = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    nan.positions[0].x = std::nanf("");
    EXPECT_EQ(validateMesh(nan).nonFiniteVertices, 1u);
    EXPECT_THROW(requireUsable(validateMesh(nan), "nan.obj"), InvalidMesh);
    auto inf = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    inf.positions[1].z = INFINITY;
    EXPECT_THROW(requireUsable(validateMesh(inf), "inf.obj"), InvalidMesh);
    auto bad = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    bad.triangles[2].x = 1000;
    EXPECT_EQ(validateMesh(bad).badIndices, 1u);
    EXPECT_THROW(requireUsable(validateMesh(bad), "bad.obj"), InvalidMesh);
}

/// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), faces facing out.
TriangleMesh tetrahedron() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

TEST(ValidateMesh, MinusZeroIsTheSameVertexAsZeroForEveryCount) {
    // One face reaches the origin through a second vertex written "-0 0 0",
    // as some exporters write it: the same point, so the mesh is closed, by
    // validation as by the winding code's boundary edges.
    TriangleMesh m = tetrahedron();
    m.positions.push_back({-0.0f, 0.0f, -0.0f});
    m.triangles[1].x = 4;
    ASSERT_TRUE(std::signbit(m.positions[4].x));
    const MeshReport r = validateMesh(m);
    EXPECT_EQ(r.boundaryEdges, 0u);
    EXPECT_TRUE(r.oriented()) << r.summary();
    EXPECT_EQ(r.isolatedVertices, 0u);
    EXPECT_EQ(r.summary(), "closed, 4 triangles, 5 vertices");
    EXPECT_TRUE(meshBoundaryEdges(m).empty());

    // Removing one face opens three edges, counted alike both ways.
    m.triangles.pop_back();
    EXPECT_EQ(validateMesh(m).boundaryEdges, 3u);
    EXPECT_EQ(meshBoundaryEdges(m).size(), 2u * 3u);
}

/// meshBoundaryEdges the slow, obvious way: positions welded in a std::map
/// keyed by value, ids in the order of first occurrence, the net use of each
/// (low, high) edge in a std::map, edges listed in that map's order.
std::vector<glm::vec3> referenceBoundaryEdges(const TriangleMesh& m) {
    std::map<std::tuple<float, float, float>, std::uint32_t> ids;
    std::vector<std::uint32_t> id;
    std::vector<glm::vec3> where;
    for (const glm::vec3& p : m.positions) {
        const auto [it, added] = ids.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(where.size()));
        if (added) where.push_back(p);
        id.push_back(it->second);
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> net;
    for (const glm::uvec3& t : m.triangles)
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = id[t[e]], b = id[t[(e + 1) % 3]];
            if (a < b) ++net[{a, b}];
            else if (b < a) --net[{b, a}];
        }
    std::vector<glm::vec3> edges;
    for (const auto& [key, uses] : net)
        for (int k = 0; k < std::abs(uses); ++k) {
            edges.push_back(where[uses > 0 ? key.first : key.second]);
            edges.push_back(where[uses > 0 ? key.second : key.first]);
        }
    return edges;
}

TEST(MeshBoundaryEdges, EqualTheReferenceOnMessySoups) {
    // Positions on a coarse lattice (many written twice, -0 beside +0),
    // random triangles (repeated and degenerate edges, edges used many times
    // one way): every edge, its multiplicity, orientation and place in the list.
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> lattice(0, 12);
    for (int round = 0; round < 4; ++round) {
        TriangleMesh m;
        for (int k = 0; k < 2000; ++k) {
            const float x = float(lattice(rng) - 6) * 0.25f;
            m.positions.push_back({x == 0.0f && k % 2 ? -0.0f : x, float(lattice(rng)) * 0.5f, float(lattice(rng) % 3)});
        }
        for (int k = 0; k < 3000 + 1000 * round; ++k)
            m.triangles.push_back({std::uint32_t(rng() % 2000), std::uint32_t(rng() % 2000), std::uint32_t(rng() % 2000)});
        const std::vector<glm::vec3> expected = referenceBoundaryEdges(m), edges = meshBoundaryEdges(m);
        ASSERT_EQ(edges.size(), expected.size());
        EXPECT_GT(edges.size(), 1000u);
        for (std::size_t k = 0; k < edges.size(); ++k) ASSERT_EQ(edges[k], expected[k]) << "endpoint " << k;
    }
}

TEST(ValidateMesh, SkippedFacesAreNamedInTheSummary) {
    TriangleMesh m = tetrahedron();
    m.skippedFaces = 2;
    const MeshReport r = validateMesh(m);
    EXPECT_EQ(r.skippedFaces, 2u);
    EXPECT_TRUE(r.usable());
    EXPECT_EQ(r.summary(), "closed, 4 triangles, 4 vertices, 2 faces of fewer than 3 vertices skipped");
    TriangleMesh none;
    none.skippedFaces = 1;
    EXPECT_EQ(validateMesh(none).summary(), "empty: no triangles (1 face of fewer than 3 vertices skipped)");
}

/// validateMesh's counts the slow, obvious way: std::map and std::set.
MeshReport referenceReport(const TriangleMesh& m) {
    MeshReport r;
    r.vertexCount = m.positions.size();
    r.triangleCount = m.triangles.size();
    std::map<std::tuple<float, float, float>, std::uint32_t> at; // compares as floats: -0 == +0
    std::vector<std::uint32_t> id(m.positions.size());
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const glm::vec3 p = m.positions[i];
        id[i] = at.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(i)).first->second;
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> uses; // (lo, hi) -> (uses, lo->hi)
    std::set<std::uint32_t> used;
    std::multiset<std::array<std::uint32_t, 3>> sets;
    bool anyBounds = false;
    for (const glm::uvec3& t : m.triangles) {
        if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) {
            ++r.badIndices;
            continue;
        }
        const std::uint32_t w[3] = {id[t.x], id[t.y], id[t.z]};
        used.insert(w, w + 3);
        const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
        for (const glm::vec3& p : {a, b, c}) { // the test's positions are finite
            r.bounds.lo = anyBounds ? glm::min(r.bounds.lo, p) : p;
            r.bounds.hi = anyBounds ? glm::max(r.bounds.hi, p) : p;
            anyBounds = true;
        }
        const bool collapsed = w[0] == w[1] || w[1] == w[2] || w[0] == w[2];
        if (collapsed || glm::length(glm::cross(b - a, c - a)) == 0.0f) ++r.degenerateTriangles;
        if (collapsed) continue;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t p = w[e], q = w[(e + 1) % 3];
            auto& u = uses[{std::min(p, q), std::max(p, q)}];
            ++u.first;
            u.second += p < q;
        }
        std::array<std::uint32_t, 3> s = {w[0], w[1], w[2]};
        std::sort(s.begin(), s.end());
        r.duplicateTriangles += sets.count(s) > 0;
        sets.insert(s);
    }
    for (const auto& [edge, u] : uses) {
        r.boundaryEdges += u.first == 1;
        r.nonManifoldEdges += u.first > 2;
        r.oddNonManifoldEdges += u.first > 2 && u.first % 2 == 1;
        r.inconsistentEdges += u.first % 2 == 0 && 2 * u.second != u.first;
        r.windingBoundaryEdges += std::size_t(std::abs(2 * u.second - u.first));
    }
    for (std::size_t i = 0; i < m.positions.size(); ++i) r.isolatedVertices += used.count(id[i]) == 0;
    return r;
}

TEST(ValidateMesh, CountsAgreeWithAnObviousReferenceOnAnyNumberOfThreads) {
    // An untidy mesh large enough to be split over threads: a closed torus
    // grid, then duplicated vertices (some as -0), flipped, repeated,
    // collapsed, dangling and out-of-range triangles, and unused vertices.
    const TriangleMesh torus = solids::torus({0, 0, 0}, 1.0f, 0.4f, 400).mesh;
    ASSERT_GT(torus.triangles.size(), 100000u);
    TriangleMesh m = torus;
    std::mt19937 random(7);
    const auto any = [&](std::size_t n) { return std::uint32_t(std::uniform_int_distribution<std::size_t>(0, n - 1)(random)); };
    m.positions.push_back({-0.0f, 0.0f, 0.0f});
    m.positions.push_back({0.0f, -0.0f, 0.0f});
    for (int k = 0; k < 2000; ++k) { // a triangle's corner moved to a twin of its vertex
        glm::uvec3& t = m.triangles[any(torus.triangles.size())];
        m.positions.push_back(m.positions[t.x]);
        t.x = std::uint32_t(m.positions.size() - 1);
    }
    for (int k = 0; k < 3000; ++k) {
        glm::uvec3& t = m.triangles[any(torus.triangles.size())];
        switch (k % 6) {
        case 0: std::swap(t.y, t.z); break;                                                  // flipped
        case 1: m.triangles.push_back(t); break;                                             // repeated
        case 2: m.triangles.push_back({t.x, t.x, t.y}); break;                               // collapsed
        case 3: m.triangles.push_back({t.x, t.y, any(m.positions.size())}); break;           // dangling
        case 4: m.triangles.push_back({t.x, std::uint32_t(m.positions.size() + k), t.y}); break; // out of range
        case 5: m.positions.push_back({float(k), 5.0f, 5.0f}); break;                         // unused
        }
    }
    m.triangles.push_back({std::uint32_t(torus.positions.size()), std::uint32_t(torus.positions.size() + 1), 0});
    const MeshReport want = referenceReport(m);
    EXPECT_GT(want.boundaryEdges, 0u);
    EXPECT_GT(want.nonManifoldEdges, 0u);
    EXPECT_GT(want.oddNonManifoldEdges, 0u);
    EXPECT_GT(want.inconsistentEdges, 0u);
    EXPECT_GT(want.duplicateTriangles, 0u);
    EXPECT_GT(want.degenerateTriangles, 0u);
    EXPECT_GT(want.isolatedVertices, 0u);
    EXPECT_GT(want.badIndices, 0u);
    for (unsigned threads : {1u, 2u, 3u, 0u}) {
        const MeshReport got = validateMesh(m, threads);
        EXPECT_EQ(got.summary(), want.summary()) << threads << " threads";
        EXPECT_EQ(got.boundaryEdges, want.boundaryEdges);
        EXPECT_EQ(got.nonManifoldEdges, want.nonManifoldEdges);
        EXPECT_EQ(got.oddNonManifoldEdges, want.oddNonManifoldEdges);
        EXPECT_EQ(got.inconsistentEdges, want.inconsistentEdges);
        EXPECT_EQ(got.windingBoundaryEdges, want.windingBoundaryEdges);
        EXPECT_EQ(got.duplicateTriangles, want.duplicateTriangles);
        EXPECT_EQ(got.degenerateTriangles, want.degenerateTriangles);
        EXPECT_EQ(got.isolatedVertices, want.isolatedVertices);
        EXPECT_EQ(got.badIndices, want.badIndices);
        EXPECT_EQ(got.bounds.lo, want.bounds.lo);
        EXPECT_EQ(got.bounds.hi, want.bounds.hi);
        const Box bounds = validateMesh(torus, threads).bounds, one = validateMesh(torus, 1).bounds;
        EXPECT_EQ(bounds.lo, one.lo);
        EXPECT_EQ(bounds.hi, one.hi);
    }
    EXPECT_TRUE(validateMesh(torus, 2).oriented());
}

} // namespace
} // namespace vds

namespace vds {
namespace {

/// Two closed boxes, the second turned inside out (every triangle reversed):
/// closed and consistently oriented edge by edge, yet its second body faces
/// inward (the multibody case).
TriangleMesh oneBodyInsideOut() {
    const TriangleMesh outward = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    TriangleMesh inward = solids::box({2, 0, 0}, {3, 1, 1}).mesh;
    for (glm::uvec3& t : inward.triangles) std::swap(t.y, t.z);
    return solids::merge(outward, inward);
}

// One account: the counts, the word, what each rule answers (asked of the
// exact classifier, independently of the validation) and the sprite's status.
TEST(MeshAccount, AClosedMeshWithOneBodyInsideOutIsToldAsMisoriented) {
    const TriangleMesh m = oneBodyInsideOut();
    const MeshReport r = validateMesh(m);
    EXPECT_TRUE(r.closed());
    EXPECT_TRUE(r.oriented()); // no edge is at fault: only the part's volume tells
    EXPECT_EQ(r.insideOutParts, 1u);
    EXPECT_EQ(r.windingBoundaryEdges, 0u);
    EXPECT_TRUE(r.misoriented());
    EXPECT_STREQ(r.status(), "mis-oriented");
    EXPECT_EQ(r.summary(), "closed but mis-oriented (1 inside-out part), 24 triangles, 16 vertices");
    const std::string message = misorientedMessage(r, "multibody.stl");
    for (const char* says : {"multibody.stl is closed but mis-oriented (1 inside-out part)", "the parity rule",
                             "the winding rule counts an inside-out part inside too",
                             "the generalized winding number, an integer here, is read as the winding rule",
                             "flip the inward-facing triangles"})
        EXPECT_NE(message.find(says), std::string::npos) << says << "\n" << message;
    EXPECT_EQ(insideWarning(r, Rule::GeneralizedWinding), message.substr(0, 0) + misorientedMessage(r, "the mesh"));

    // What the message says each rule answers, from the exact classifier.
    const ExactClassifier exact(m);
    EXPECT_EQ(exact.boundaryEdgeCount(), r.windingBoundaryEdges);
    const glm::vec3 inOutward(0.5f, 0.5f, 0.5f), inInward(2.5f, 0.5f, 0.5f);
    EXPECT_TRUE(exact.contains(inInward, Rule::Parity));
    EXPECT_TRUE(exact.contains(inInward, Rule::Winding));
    EXPECT_TRUE(exact.contains(inInward, Rule::GeneralizedWinding)); // read as the winding rule
    EXPECT_NEAR(exact.generalizedWinding(inInward), -1.0, 1e-9);
    EXPECT_TRUE(exact.contains(inOutward, Rule::GeneralizedWinding));

    // The sprite's status says the same word, from its file's fields.
    BakeOptions options;
    options.resolution = 16;
    options.method = BakeMethod::Cpu;
    const Sprite s = bakeCpu(m, options);
    EXPECT_EQ(s.status, SolidStatus::Open);
    EXPECT_STREQ(statusWord(s.status, s.validation), "mis-oriented");
    EXPECT_EQ(s.validation, r.summary());
}

/// A mesh turned inside out: every triangle reversed.
TriangleMesh reversed(TriangleMesh m) {
    for (glm::uvec3& t : m.triangles) std::swap(t.y, t.z);
    return m;
}

// The parts' volumes are summed over fixed chunks of 65,536 triangles where
// there are few parts, over all the triangles at once where there are many:
// an inside-out part is found either way, and any number of threads finds
// the same report.
TEST(MeshAccount, InsideOutPartsAreFoundInLargeMeshesAndAmongManyParts) {
    const TriangleMesh big = reversed(solids::sphere({0, 0, 0}, 1.0f, 370).mesh);
    ASSERT_GT(big.triangles.size(), 2u * 65536u);
    TriangleMesh many = reversed(solids::box({0, 0, 0}, {0.5f, 0.5f, 0.5f}).mesh);
    for (int k = 1; k < 300; ++k)
        many = solids::merge(many, solids::box({float(k), 0, 0}, {float(k) + 0.5f, 0.5f, 0.5f}).mesh);
    for (const TriangleMesh& m : {solids::merge(big, solids::box({3, 3, 3}, {4, 4, 4}).mesh), many}) {
        const MeshReport r = validateMesh(m, 1);
        EXPECT_TRUE(r.closed());
        EXPECT_EQ(r.insideOutParts, 1u);
        EXPECT_FALSE(r.coplanar);
        for (unsigned threads : {2u, 3u}) {
            const MeshReport again = validateMesh(m, threads);
            EXPECT_EQ(again.summary(), r.summary()) << threads;
            EXPECT_EQ(again.insideOutParts, r.insideOutParts) << threads;
            EXPECT_EQ(again.bounds.lo, r.bounds.lo) << threads;
            EXPECT_EQ(again.bounds.hi, r.bounds.hi) << threads;
        }
    }
    // The same sphere facing outward has none.
    EXPECT_EQ(validateMesh(reversed(big), 2).insideOutParts, 0u);
}

// The weld splits the vertices among the threads by their hash: a soup of
// more than 65,536 vertices (every triangle with its own three, a few
// vertices not finite, unused) welds into the closed sphere it came from,
// with the same report and the same edge partners for any number of threads.
TEST(MeshAccount, AWeldOfManyVerticesIsTheSameForAnyNumberOfThreads) {
    const TriangleMesh sphere = solids::sphere({0.3f, -0.1f, 0.2f}, 1.0f, 160).mesh;
    TriangleMesh soup;
    for (const glm::uvec3& t : sphere.triangles) {
        const auto n = std::uint32_t(soup.positions.size());
        soup.positions.insert(soup.positions.end(), {sphere.positions[t.x], sphere.positions[t.y], sphere.positions[t.z]});
        soup.triangles.push_back({n, n + 1, n + 2});
    }
    const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
    soup.positions.insert(soup.positions.begin() + 1000, 3, glm::vec3(nan, 0.0f, inf)); // unused: indices shift past them
    for (glm::uvec3& t : soup.triangles)
        for (int k = 0; k < 3; ++k) t[k] += t[k] >= 1000 ? 3 : 0;
    ASSERT_GT(soup.positions.size(), 65536u);
    detail::MeshFinds one;
    const MeshReport r = detail::validateMesh(soup, 1, one);
    EXPECT_TRUE(r.closed());
    EXPECT_EQ(r.boundaryEdges, 0u);
    EXPECT_EQ(r.inconsistentEdges, 0u);
    EXPECT_EQ(r.nonFiniteVertices, 3u);
    EXPECT_EQ(r.isolatedVertices, 3u);
    for (unsigned threads : {2u, 3u, 4u}) {
        detail::MeshFinds again;
        EXPECT_EQ(detail::validateMesh(soup, threads, again).summary(), r.summary()) << threads;
        EXPECT_TRUE(again.partners == one.partners) << threads;
        EXPECT_TRUE(again.facings == one.facings) << threads;
    }
}

// A sheet of more than 65,536 triangles in the plane z = 0, the largest in
// the last chunk; the first chunk's largest is a loose triangle tilted off
// that plane by less than the tolerance at its corners but far more across
// the sheet. The plane is the largest triangle's, found across the chunks:
// coplanar; lifting a vertex of the first chunk makes it not.
TEST(MeshAccount, APlaneIsFoundAcrossChunksOfTriangles) {
    TriangleMesh sheet;
    sheet.positions = {{0, 0, 0}, {1.5f, 0, 1e-4f}, {0, 1.5f, 0}};
    sheet.triangles = {{0, 1, 2}};
    constexpr std::uint32_t kSide = 200; // 2 * 199^2 = 79,202 triangles
    for (std::uint32_t j = 0; j < kSide; ++j)
        for (std::uint32_t i = 0; i < kSide; ++i)
            sheet.positions.push_back({float(i), float(j) + (j + 1 == kSide ? 5.0f : 0.0f), 0.0f}); // the last row wide
    for (std::uint32_t j = 0; j + 1 < kSide; ++j)
        for (std::uint32_t i = 0; i + 1 < kSide; ++i) {
            const std::uint32_t v = 3 + j * kSide + i;
            sheet.triangles.push_back({v, v + 1, v + kSide});
            sheet.triangles.push_back({v + 1, v + kSide + 1, v + kSide});
        }
    EXPECT_TRUE(validateMesh(sheet, 1).coplanar);
    EXPECT_TRUE(validateMesh(sheet, 2).coplanar);
    sheet.positions[3 + kSide + 1].z += 0.5f;
    EXPECT_FALSE(validateMesh(sheet, 2).coplanar);
}

// The closed box with one triangle reversed: three conflicting edges, each
// counted twice by the generalized winding number's boundary, as the exact
// classifier and the sprite count it; an open box's counts agree the same way.
TEST(MeshAccount, EveryCountOfOneMeshAgrees) {
    auto flipped = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
    auto open = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    open.triangles.pop_back();
    for (const TriangleMesh& m : {flipped, open}) {
        const MeshReport r = validateMesh(m);
        const ExactClassifier exact(m);
        EXPECT_EQ(exact.boundaryEdgeCount(), r.windingBoundaryEdges);
        EXPECT_NE(exact.summary().find(windingBoundaryText(r.windingBoundaryEdges)), std::string::npos) << exact.summary();
        BakeOptions options;
        options.resolution = 16;
        options.method = BakeMethod::Cpu;
        const Sprite s = bakeCpu(m, options);
        EXPECT_EQ(s.boundaryEdges.size() / 2, r.windingBoundaryEdges);
        EXPECT_STREQ(statusWord(s.status, s.validation), r.status());
    }
    EXPECT_STREQ(validateMesh(open).status(), "open");
    EXPECT_EQ(validateMesh(open).windingBoundaryEdges, 3u);
    EXPECT_EQ(validateMesh(flipped).windingBoundaryEdges, 6u);
    // With a boundary (conflicting edges), the generalized winding number is the continuous value above 1/2.
    const MeshReport f = validateMesh(flipped);
    EXPECT_NE(misorientedMessage(f, "").find("the winding rule does not define inside"), std::string::npos);
    EXPECT_NE(misorientedMessage(f, "").find("the generalized winding number sees an inside-out part as outside"),
              std::string::npos);
    const TriangleMesh box = solids::box({0, 0, 0}, {1, 1, 1}).mesh;
    EXPECT_STREQ(validateMesh(box).status(), "closed");
    EXPECT_EQ(validateMesh(box).insideOutParts, 0u);
    // A reversed sphere inside an outward one is a cavity (winding 0 inside it), not an inside-out part.
    const MeshReport shell = validateMesh(solids::shell({0, 0, 0}, 1.0f, 0.6f, 24).mesh);
    EXPECT_EQ(shell.insideOutParts, 0u);
    EXPECT_STREQ(shell.status(), "closed");
}

} // namespace
} // namespace vds

namespace vds {
namespace {

// A sheet in the tilted plane x = y has extent along every axis, yet bounds
// no volume: seen along z it is edge-on (a sprite of 0 layers). It is
// refused as the axis-aligned sheets are; a thin solid box is not.
TEST(MeshAccount, AnEdgeOnSheetIsFlatLikeTheOthers) {
    TriangleMesh sheet;
    sheet.positions = {{0, 0, 0}, {1, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    sheet.triangles = {{0, 1, 2}, {2, 1, 3}};
    const MeshReport r = validateMesh(sheet);
    EXPECT_TRUE(r.coplanar);
    EXPECT_TRUE(r.flat());
    try {
        requireVolume(r, "tilted.obj");
        ADD_FAILURE() << "an edge-on sheet was taken for a volume";
    } catch (const InvalidMesh& e) {
        EXPECT_NE(std::string(e.what()).find("tilted.obj is flat (all its triangles lie in one plane)"), std::string::npos)
            << e.what();
    }
    BakeOptions options;
    options.resolution = 16;
    options.axis = Axis::Z;
    EXPECT_THROW(bakeCpu(sheet, options), InvalidMesh);
    const MeshReport thin = validateMesh(solids::box({0, 0, 0}, {1, 1, 1e-3f}).mesh);
    EXPECT_FALSE(thin.coplanar);
    EXPECT_FALSE(thin.flat());
}

} // namespace
} // namespace vds
