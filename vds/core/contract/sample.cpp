// Area-weighted surface samples: a specified counter-based generator
// (SplitMix64, Steele, Lea and Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014) and the square-root map of two uniforms to a
// uniform point of a triangle (Osada, Funkhouser, Chazelle and Dobkin,
// "Shape distributions", ACM TOG 2002, section 4.2).
#include <vds/sample.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <vds/error.h>

namespace vds {

double sampleUniform(std::uint64_t seed, std::uint64_t index) {
    std::uint64_t z = seed + (index + 1) * 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53;
}

namespace {

/// Running sums of the triangles' areas (twice the area: only ratios count).
std::vector<double> runningAreas(const MeshView& mesh) {
    std::vector<double> sums(mesh.triangleCount);
    double sum = 0.0;
    for (std::size_t t = 0; t < mesh.triangleCount; ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        if (tri.x >= mesh.positionCount || tri.y >= mesh.positionCount || tri.z >= mesh.positionCount)
            throw InvalidMesh("cannot sample the surface: triangle " + std::to_string(t) + " has an index out of range");
        const glm::dvec3 a(mesh.positions[tri.x]), b(mesh.positions[tri.y]), c(mesh.positions[tri.z]);
        const glm::dvec3 e1 = b - a, e2 = c - a;
        const double x = e1.y * e2.z - e1.z * e2.y, y = e1.z * e2.x - e1.x * e2.z, z = e1.x * e2.y - e1.y * e2.x;
        const double area = std::sqrt(x * x + y * y + z * z);
        if (!std::isfinite(area))
            throw InvalidMesh("cannot sample the surface: triangle " + std::to_string(t) + " has a corner that is not finite");
        sum += area;
        sums[t] = sum;
    }
    if (!(sum > 0.0))
        throw InvalidMesh("no area to sample: the mesh's triangles (" + std::to_string(mesh.triangleCount) +
                          ") all have zero area");
    return sums;
}

} // namespace

void sampleSurface(const MeshView& mesh, std::size_t count, std::uint64_t seed, double* points,
                   std::uint32_t* triangles) {
    const std::vector<double> sums = runningAreas(mesh);
    const double total = sums.back();
    // u0 * total may round up to the total: then the last triangle of non-zero area.
    const std::size_t last = std::size_t(std::lower_bound(sums.begin(), sums.end(), total) - sums.begin());
    for (std::size_t k = 0; k < count; ++k) {
        const double u0 = sampleUniform(seed, 3 * std::uint64_t(k));
        const double r = std::sqrt(sampleUniform(seed, 3 * std::uint64_t(k) + 1));
        const double u2 = sampleUniform(seed, 3 * std::uint64_t(k) + 2);
        const std::size_t t =
            std::min(last, std::size_t(std::upper_bound(sums.begin(), sums.end(), u0 * total) - sums.begin()));
        const glm::uvec3 tri = mesh.triangles[t];
        const glm::dvec3 a(mesh.positions[tri.x]), b(mesh.positions[tri.y]), c(mesh.positions[tri.z]);
        const double w0 = 1.0 - r, w1 = r * (1.0 - u2), w2 = r * u2;
        for (int axis = 0; axis < 3; ++axis) points[3 * k + axis] = w0 * a[axis] + w1 * b[axis] + w2 * c[axis];
        if (triangles) triangles[k] = std::uint32_t(t);
    }
}

SurfaceSamples sampleSurface(const MeshView& mesh, std::size_t count, std::uint64_t seed) {
    SurfaceSamples samples;
    samples.points.resize(3 * count);
    samples.triangles.resize(count);
    sampleSurface(mesh, count, seed, samples.points.data(), samples.triangles.data());
    return samples;
}

} // namespace vds
