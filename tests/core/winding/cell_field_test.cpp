// A cell's field (<vds/detail/cell_field.h>): the boundary term's far part
// interpolated over a box, against the per-edge sum (antipodal.h) over the
// far edges, the independent exact form; and the labels of cells that
// build fields, against the crossing count plus the per-edge sum.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <vds/mesh.h>

#include <vds/detail/antipodal.h>
#include <vds/detail/boundary_caps.h>
#include <vds/detail/cap_loops.h>
#include <vds/detail/caps_surface.h>
#include <vds/detail/cell_field.h>
#include <vds/detail/chain_labels.h>
#include <vds/detail/projected_mesh.h>
#include "solids.h"

namespace vds::detail {
namespace {

struct Named {
    std::string name;
    TriangleMesh mesh;
};

// Open meshes whose boundaries differ: one long loop, a dozen round holes,
// a soup of many small loops, and a wavy rim that rises and falls along
// the axis (its strips' sweeps pass over and under the boxes).
std::vector<Named> openMeshes() {
    std::vector<Named> out;
    out.push_back({"cup", solids::sphereCup()});
    out.push_back({"holes", solids::sphereWithHoles()});
    out.push_back({"soup", solids::looseTriangles(120, 0.15f, 41)});
    out.push_back({"wavy rim", solids::openSphere(40, 96, [](const glm::vec3& c) {
                       return c.z < 0.3f + 0.25f * std::sin(7.0f * std::atan2(c.y, c.x));
                   })});
    return out;
}

// The far part the field stands for, exactly: the per-edge sum over every
// edge less that over the near nodes' edges.
double farPart(const ChainLabels& labels, const CellField& field, const std::vector<glm::vec3>& all,
               const glm::dvec3& q) {
    std::vector<glm::vec3> near;
    for (const std::uint32_t i : field.nearNodes()) {
        const ChainNode& n = labels.chains()[i];
        near.insert(near.end(), labels.edges().begin() + 2 * std::ptrdiff_t(n.edgeFirst),
                    labels.edges().begin() + 2 * std::ptrdiff_t(n.edgeFirst + n.edgeCount));
    }
    return boundaryTermExact(all.data(), all.size() / 2, 2, q) - boundaryTermExact(near.data(), near.size() / 2, 2, q);
}

TEST(CellField, RestErrsByNoMoreThanItsBound) {
    // Boxes of three sizes all over the meshes, points in each (corners
    // and faces among them): the interpolated far part within its bound
    // of the far edges' per-edge sum, and the bound small enough to use
    // for most boxes clear of the boundary.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> centre(-1.1, 1.1), unit(0.0, 1.0);
    for (const Named& m : openMeshes()) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(m.mesh));
        const CapLoops loops(edges.data(), edges.size() / 2, Axis::Z);
        const ChainLabels labels(loops);
        ASSERT_TRUE(loops.closed()) << m.name;
        std::size_t built = 0, useful = 0;
        double worst = 0.0;
        for (int box = 0; box < 36; ++box) {
            const double side = 0.05 * double(1 << (box % 3));
            const glm::dvec3 lo(centre(rng), centre(rng), centre(rng)), hi = lo + side;
            CellField field;
            if (!field.build(labels, lo, hi, side, 1.0, std::size_t(-1))) continue;
            ++built;
            useful += field.error() < 0.05;
            for (int k = 0; k < 40; ++k) {
                glm::dvec3 t(unit(rng), unit(rng), unit(rng));
                if (k < 8) t = glm::dvec3(k & 1, (k >> 1) & 1, (k >> 2) & 1); // the corners
                if (k >= 8 && k < 14) t[k % 3] = double(k & 1);               // on faces
                const glm::vec3 q(lo + t * (hi - lo));
                const double exact = farPart(labels, field, edges, glm::dvec3(q));
                const double error = std::fabs(field.rest(q) - exact);
                ASSERT_LE(error, field.error()) << m.name << " box " << box << " at " << q.x << " " << q.y << " " << q.z;
                worst = std::max(worst, error / field.error());
            }
        }
        EXPECT_GT(built, 18u) << m.name;
        EXPECT_GT(useful, 9u) << m.name;
        EXPECT_GT(worst, 1e-4) << m.name; // the bound is not vacuous
    }
}

TEST(CellField, ABoxLeavesItsQueriesOnlyTheNodesNearItsColumn) {
    // A circle of 2,048 edges in z = 0 and a box of side 0.1 at its
    // centre: every edge lies 0.9 beyond the box across the axis, so the
    // field takes them all (no near node) and its bound is small; a box
    // beside the circle leaves the nodes within its margin, a few chains of
    // the circle, and the rest to the field.
    std::vector<glm::vec3> edges;
    constexpr int kEdges = 2048;
    for (int k = 0; k < kEdges; ++k)
        for (const int j : {k, k + 1}) {
            const double phi = 2.0 * 3.14159265358979323846 * (j % kEdges) / kEdges;
            edges.emplace_back(float(std::cos(phi)), float(std::sin(phi)), 0.0f);
        }
    const CapLoops loops(edges.data(), edges.size() / 2, Axis::Z);
    const ChainLabels labels(loops);
    CellField middle;
    ASSERT_TRUE(middle.build(labels, glm::dvec3(-0.05), glm::dvec3(0.05), 0.1, 1.0, std::size_t(-1)));
    EXPECT_TRUE(middle.nearNodes().empty());
    EXPECT_LT(middle.error(), 1e-3);
    const glm::vec3 q(0.01f, -0.02f, 0.03f);
    EXPECT_NEAR(middle.rest(q), boundaryTermExact(edges.data(), kEdges, 2, glm::dvec3(q)), middle.error());
    CellField beside;
    ASSERT_TRUE(beside.build(labels, glm::dvec3(0.8, -0.05, -0.05), glm::dvec3(0.9, 0.05, 0.05), 0.1, 1.0, std::size_t(-1)));
    std::size_t nearEdges = 0;
    for (const std::uint32_t i : beside.nearNodes()) nearEdges += labels.chains()[i].edgeCount;
    EXPECT_GT(nearEdges, 0u);
    EXPECT_LT(nearEdges, kEdges / 8);
    // A limit on the near nodes turns the field down.
    CellField limited;
    EXPECT_FALSE(limited.build(labels, glm::dvec3(0.8, -0.05, -0.05), glm::dvec3(0.9, 0.05, 0.05), 0.1, 1.0,
                               beside.nearNodes().size()));
}

TEST(CellField, CellsThatBuildFieldsLabelAsThePerEdgeSum) {
    // Queries packed in a few small regions near each surface, asked over
    // and over: their cells spend work enough to build fields (and their
    // busy cells' fine cells theirs), and answer from them from then on.
    // The same labels as the crossing count plus the per-edge sum, round
    // after round, and fields were built (not in every mesh: beside the
    // cup's one round rim the cells' plans cost less than a field would).
    std::size_t fields = 0;
    std::mt19937 rng(43);
    std::uniform_real_distribution<float> within(-0.04f, 0.04f);
    for (const Named& m : openMeshes()) {
        const std::vector<glm::vec3> edges = boundaryEdges(MeshView(m.mesh));
        const ProjectedMesh projected(MeshView(m.mesh), Axis::Z);
        const ProjectedSurface surface(projected);
        const Box domain{glm::vec3(-1.0f), glm::vec3(1.0f)};
        const BoundaryCaps caps(edges.data(), edges.size() / 2, Axis::Z, &domain, &surface);
        std::vector<glm::vec3> at;
        std::vector<bool> expected;
        for (std::size_t spot = 0; spot < 5; ++spot) {
            const glm::uvec3 t = m.mesh.triangles[spot * m.mesh.triangles.size() / 5];
            const glm::vec3 c = (m.mesh.positions[t[0]] + m.mesh.positions[t[1]] + m.mesh.positions[t[2]]) / 3.0f;
            for (int i = 0; i < 1500; ++i) {
                const glm::vec3 q = c + glm::vec3(within(rng), within(rng), within(rng));
                at.push_back(q);
                expected.push_back(generalizedWindingInside(double(projected.winding(q)) +
                                                            boundaryTermExact(edges.data(), edges.size() / 2, 2, glm::dvec3(q))));
            }
        }
        for (int round = 0; round < 8; ++round)
            for (std::size_t i = 0; i < at.size(); ++i)
                ASSERT_EQ(caps.inside(at[i]), expected[i])
                    << m.name << " round " << round << " at " << at[i].x << " " << at[i].y << " " << at[i].z;
        fields += caps.fieldsBuilt();
    }
    EXPECT_GT(fields, 10u);
}

} // namespace
} // namespace vds::detail
