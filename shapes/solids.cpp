#include "solids.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <glm/geometric.hpp>

#include <vds/error.h>

namespace vds::solids {
namespace {

constexpr float kPi = 3.14159265358979323846f;

float boxDistance(const Solid& s, const glm::vec3& p) {
    const glm::vec3 q = glm::abs(p - s.centre) - 0.5f * s.size;
    const glm::vec3 outside = glm::max(q, glm::vec3(0.0f));
    return glm::length(outside) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
}

float sphereDistance(const Solid& s, const glm::vec3& p) { return glm::length(p - s.centre) - s.size.x; }

float shellDistance(const Solid& s, const glm::vec3& p) {
    const float d = glm::length(p - s.centre);
    return std::max(d - s.size.x, s.size.y - d);
}

float torusDistance(const Solid& s, const glm::vec3& p) {
    const glm::vec3 q = p - s.centre;
    const float ring = std::sqrt(q.x * q.x + q.y * q.y) - s.size.x;
    return std::sqrt(ring * ring + q.z * q.z) - s.size.y;
}

float segmentDistance(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 ab = b - a;
    const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}

float knotDistance(const Solid& s, const glm::vec3& p) {
    float best = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < s.line.size(); ++i)
        best = std::min(best, segmentDistance(p, s.line[i], s.line[(i + 1) % s.line.size()]));
    return best - s.size.y;
}

// Two boxes: centre/size hold box A, the mesh's second half is box B; the
// distance is the union's, recomputed from the mesh's vertex ranges.
float unionDistance(const Solid& s, const glm::vec3& p) {
    Solid a;
    a.centre = s.centre;
    a.size = s.size;
    const auto& v = s.mesh.positions;
    glm::vec3 lo = v[8], hi = v[8];
    for (std::size_t i = 8; i < 16; ++i) {
        lo = glm::min(lo, v[i]);
        hi = glm::max(hi, v[i]);
    }
    Solid b;
    b.centre = 0.5f * (lo + hi);
    b.size = hi - lo;
    return std::min(boxDistance(a, p), boxDistance(b, p));
}

void appendBox(TriangleMesh& m, const glm::vec3& lo, const glm::vec3& hi) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int k = 0; k < 8; ++k)
        m.positions.emplace_back((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
    // Outward counter-clockwise quads, as corner bit patterns (x=1, y=2, z=4).
    const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(base + q[0], base + q[1], base + q[2]);
        m.triangles.emplace_back(base + q[0], base + q[2], base + q[3]);
    }
}

// UV sphere; `inward` flips the orientation (for a shell's inner surface).
void appendSphere(TriangleMesh& m, const glm::vec3& c, float r, std::uint32_t segments, bool inward) {
    const std::uint32_t rings = segments / 2;
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back(c + glm::vec3(0, 0, r));  // north pole
    for (std::uint32_t i = 1; i < rings; ++i) {
        const float phi = kPi * float(i) / float(rings);
        for (std::uint32_t j = 0; j < segments; ++j) {
            const float theta = 2.0f * kPi * float(j) / float(segments);
            m.positions.push_back(c + r * glm::vec3(std::sin(phi) * std::cos(theta),
                                                    std::sin(phi) * std::sin(theta), std::cos(phi)));
        }
    }
    m.positions.push_back(c - glm::vec3(0, 0, r)); // south pole
    const std::uint32_t south = base + 1 + (rings - 1) * segments;
    auto ring = [&](std::uint32_t i, std::uint32_t j) { return base + 1 + (i - 1) * segments + (j % segments); };
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t d) {
        if (inward)
            m.triangles.emplace_back(a, d, b);
        else
            m.triangles.emplace_back(a, b, d);
    };
    for (std::uint32_t j = 0; j < segments; ++j) {
        add(base, ring(1, j), ring(1, j + 1));
        add(south, ring(rings - 1, j + 1), ring(rings - 1, j));
    }
    for (std::uint32_t i = 1; i + 1 < rings; ++i)
        for (std::uint32_t j = 0; j < segments; ++j) {
            add(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
            add(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
        }
}

float chordError(float radius, float angle) { return radius * (1.0f - std::cos(angle)); }

} // namespace

Solid box(const glm::vec3& lo, const glm::vec3& hi) {
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
        throw InvalidArgument("box: lo must be below hi on every axis");
    Solid s;
    appendBox(s.mesh, lo, hi);
    s.mesh.name = "box";
    s.centre = 0.5f * (lo + hi);
    s.size = hi - lo;
    s.signedDistance = boxDistance;
    return s;
}

Solid sphere(const glm::vec3& centre, float radius, std::uint32_t segments) {
    if (segments < 8 || !(radius > 0.0f))
        throw InvalidArgument("sphere: needs radius > 0 and at least 8 segments");
    Solid s;
    appendSphere(s.mesh, centre, radius, segments, false);
    s.mesh.name = "sphere";
    s.centre = centre;
    s.size = glm::vec3(radius, 0.0f, 0.0f);
    s.tessellationError = chordError(radius, std::sqrt(2.0f) * 2.0f * kPi / float(segments));
    s.signedDistance = sphereDistance;
    return s;
}

Solid torus(const glm::vec3& centre, float majorRadius, float minorRadius, std::uint32_t segments) {
    if (segments < 8 || !(minorRadius > 0.0f) || !(majorRadius > minorRadius))
        throw InvalidArgument("torus: needs 0 < minor < major radius and at least 8 segments");
    Solid s;
    const std::uint32_t tube = std::max<std::uint32_t>(8, segments / 2);
    for (std::uint32_t i = 0; i < segments; ++i) {
        const float u = 2.0f * kPi * float(i) / float(segments);
        for (std::uint32_t j = 0; j < tube; ++j) {
            const float v = 2.0f * kPi * float(j) / float(tube);
            const float rr = majorRadius + minorRadius * std::cos(v);
            s.mesh.positions.push_back(centre + glm::vec3(rr * std::cos(u), rr * std::sin(u), minorRadius * std::sin(v)));
        }
    }
    auto at = [&](std::uint32_t i, std::uint32_t j) { return (i % segments) * tube + (j % tube); };
    for (std::uint32_t i = 0; i < segments; ++i)
        for (std::uint32_t j = 0; j < tube; ++j) {
            s.mesh.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            s.mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    s.mesh.name = "torus";
    s.centre = centre;
    s.size = glm::vec3(majorRadius, minorRadius, 0.0f);
    const float a = 2.0f * kPi / float(segments), b = 2.0f * kPi / float(tube);
    s.tessellationError = chordError(majorRadius + minorRadius, a) + chordError(minorRadius, b);
    s.signedDistance = torusDistance;
    return s;
}

Solid shell(const glm::vec3& centre, float outer, float inner, std::uint32_t segments) {
    if (segments < 8 || !(inner > 0.0f) || !(outer > inner))
        throw InvalidArgument("shell: needs 0 < inner < outer radius and at least 8 segments");
    Solid s;
    appendSphere(s.mesh, centre, outer, segments, false);
    appendSphere(s.mesh, centre, inner, segments, true);
    s.mesh.name = "shell";
    s.centre = centre;
    s.size = glm::vec3(outer, inner, 0.0f);
    s.tessellationError = chordError(outer, std::sqrt(2.0f) * 2.0f * kPi / float(segments));
    s.signedDistance = shellDistance;
    return s;
}

Solid overlappingBoxes(const glm::vec3& loA, const glm::vec3& hiA, const glm::vec3& loB, const glm::vec3& hiB) {
    Solid s = box(loA, hiA);
    appendBox(s.mesh, loB, hiB);
    s.mesh.name = "overlapping-boxes";
    s.signedDistance = unionDistance;
    return s;
}

Solid torusKnot(const glm::vec3& centre, float scale, std::uint32_t p, std::uint32_t q, float tubeRadius,
                std::uint32_t segments, std::uint32_t tubeSegments) {
    if (p == 0 || q == 0 || segments < 16 || tubeSegments < 3 || !(scale > 0.0f) || !(tubeRadius > 0.0f) ||
        !(tubeRadius < 0.4f * scale))
        throw InvalidArgument("torusKnot: needs p, q > 0, 16 segments, 3 around, 0 < tube radius < 0.4 scale");
    const float r = 0.4f;
    auto curve = [&](double t) {
        const double a = 1.0 + r * std::cos(q * t);
        return glm::dvec3(a * std::cos(p * t), a * std::sin(p * t), r * std::sin(q * t));
    };
    Solid s;
    const double step = 2.0 * double(kPi) / double(segments), h = 1e-4;
    for (std::uint32_t i = 0; i < segments; ++i) {
        const double t = step * double(i);
        const glm::dvec3 c = curve(t), before = curve(t - h), after = curve(t + h);
        // The Frenet frame: periodic, since the line closes and never straightens.
        const glm::dvec3 tangent = glm::normalize(after - before);
        const glm::dvec3 bend = after - 2.0 * c + before;
        const glm::dvec3 binormal = glm::normalize(glm::cross(tangent, bend));
        const glm::dvec3 normal = glm::cross(binormal, tangent);
        s.line.push_back(centre + scale * glm::vec3(c));
        for (std::uint32_t j = 0; j < tubeSegments; ++j) {
            const double v = 2.0 * double(kPi) * double(j) / double(tubeSegments);
            const glm::dvec3 ring = std::cos(v) * normal + std::sin(v) * binormal;
            s.mesh.positions.push_back(centre + glm::vec3(double(scale) * c + double(tubeRadius) * ring));
        }
    }
    auto at = [&](std::uint32_t i, std::uint32_t j) { return (i % segments) * tubeSegments + (j % tubeSegments); };
    for (std::uint32_t i = 0; i < segments; ++i)
        for (std::uint32_t j = 0; j < tubeSegments; ++j) { // counter-clockwise seen from outside
            s.mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
            s.mesh.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
        }
    s.mesh.name = "torus-knot";
    s.centre = centre;
    s.size = glm::vec3(scale, tubeRadius, 0.0f);
    // The polygon around the tube, and the polyline standing in for the line.
    const float lineStep = scale * 3.0f * float(step) * float(std::max(p, q));
    s.tessellationError = chordError(tubeRadius, 2.0f * kPi / float(tubeSegments)) + lineStep * lineStep;
    s.signedDistance = knotDistance;
    return s;
}

Solid boxesSharingAnEdge(const glm::vec3& lo, float size) {
    Solid s = box(lo, lo + glm::vec3(size));
    appendBox(s.mesh, lo + glm::vec3(size, size, 0.0f), lo + glm::vec3(2.0f * size, 2.0f * size, size));
    s.mesh.name = "boxes-sharing-an-edge";
    s.signedDistance = unionDistance;
    return s;
}

TriangleMesh merge(const TriangleMesh& a, const TriangleMesh& b) {
    TriangleMesh m = a;
    const auto base = static_cast<std::uint32_t>(a.positions.size());
    m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
    for (const auto& t : b.triangles) m.triangles.push_back(t + glm::uvec3(base));
    m.name = a.name + "+" + b.name;
    return m;
}

TriangleMesh without(const TriangleMesh& mesh, bool (*drop)(const glm::vec3& centroid)) {
    TriangleMesh out = mesh;
    out.triangles.clear();
    for (const glm::uvec3& t : mesh.triangles)
        if (!drop((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0f)) out.triangles.push_back(t);
    return out;
}

TriangleMesh looseTriangles(std::uint32_t count, float size, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    TriangleMesh m;
    for (std::uint32_t k = 0; k < count; ++k) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        for (int v = 0; v < 3; ++v) m.positions.push_back(c + size * glm::vec3(u(rng), u(rng), u(rng)));
        m.triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    }
    return m;
}

TriangleMesh openSphere(int rings, int segments, const std::function<bool(const glm::vec3&)>& keep) {
    constexpr double kPi = 3.14159265358979323846;
    TriangleMesh m;
    const auto at = [&](int i, int j) {
        const double theta = kPi * i / rings, phi = 2.0 * kPi * j / segments;
        return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                         float(std::cos(theta)));
    };
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) m.positions.push_back(at(i, j));
    const auto id = [&](int i, int j) { return std::uint32_t(i * segments + (j % segments)); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const glm::vec3 c = glm::normalize(at(i, j) + at(i + 1, j + 1));
            if (!keep(c)) continue;
            if (i > 0) m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
            if (i + 1 < rings) m.triangles.push_back({id(i, j + 1), id(i + 1, j), id(i + 1, j + 1)});
        }
    return m;
}

TriangleMesh sphereCup() {
    return without(sphere({0, 0, 0}, 1.0f, 32).mesh, [](const glm::vec3& c) { return c.z > 0.5f; });
}

TriangleMesh sphereWithHoles() {
    return without(sphere({0, 0, 0}, 1.0f, 32).mesh, [](const glm::vec3& c) {
        return std::fabs(c.x) > 0.8f || (c.y > 0.7f && c.z > 0.0f);
    });
}

TriangleMesh overlappingShells() {
    const TriangleMesh a = without(sphere({0, 0, 0}, 1.0f, 24).mesh, [](const glm::vec3& c) { return c.y > 0.8f; });
    const TriangleMesh b = without(sphere({0.6f, 0.1f, 0.2f}, 0.8f, 24).mesh, [](const glm::vec3& c) { return c.x > 1.2f; });
    return merge(a, b);
}

TriangleMesh flatRimBowl(int rings, int segments) {
    TriangleMesh m;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i) // i = 0: the rim, i = rings: the pole at y = -1
        for (int j = 0; j < segments; ++j) {
            const double theta = 0.5 * pi * i / rings, phi = 2.0 * pi * j / segments;
            m.positions.emplace_back(float(std::cos(theta) * std::cos(phi)), i == 0 ? 0.0f : float(-std::sin(theta)),
                                     float(std::cos(theta) * std::sin(phi)));
        }
    const auto id = [&](int i, int j) { return std::uint32_t(i * segments + (j % segments)); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j)});
            if (i + 1 < rings) m.triangles.push_back({id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)});
        }
    return m;
}


TriangleMesh bowlWithDisk() {
    TriangleMesh mesh = flatRimBowl(16, 64);
    const std::uint32_t centre = std::uint32_t(mesh.positions.size());
    mesh.positions.emplace_back(0.0f, -0.2f, 0.0f);
    for (int j = 0; j < 32; ++j) {
        const double phi = 2.0 * 3.14159265358979323846 * j / 32;
        mesh.positions.emplace_back(float(0.6 * std::cos(phi)), -0.2f, float(0.6 * std::sin(phi)));
    }
    for (std::uint32_t j = 0; j < 32; ++j)
        mesh.triangles.push_back({centre, centre + 1 + j, centre + 1 + (j + 1) % 32});
    return mesh;
}

} // namespace vds::solids
