// vds: points on a mesh's surface, area-weighted and reproducible from a seed
// on every platform (the generator and its mapping to uniforms are written
// here, not left to a standard library's distributions).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <vds/mesh.h>

namespace vds {

/// The generator behind `sampleSurface`: draw `index` (0, 1, 2, ...) of the
/// stream `seed`, uniform in [0, 1) with 53 random bits. It is SplitMix64
/// read as a counter: z = seed + (index + 1) * 0x9E3779B97F4A7C15 (mod 2^64),
/// then z ^= z >> 30, z *= 0xBF58476D1CE4E5B9, z ^= z >> 27,
/// z *= 0x94D049BB133111EB, z ^= z >> 31; the uniform is (z >> 11) * 2^-53.
/// Any draw is had without the ones before it.
double sampleUniform(std::uint64_t seed, std::uint64_t index);

/// Writes `count` points on the triangles of `mesh`, each on a triangle
/// chosen with probability its area over the total and uniform on it.
/// Sample k takes draws u0, u1, u2 = `sampleUniform(seed, 3k + 0, 1, 2)`:
///  - its triangle is the first t whose running sum of areas exceeds
///    u0 * total (areas in double from the float corners, |(b-a) x (c-a)|
///    with the cross product's squares summed x, y, z; running sums in
///    triangle order), so a triangle of zero area is never chosen;
///  - its point is w0 a + w1 b + w2 c (summed in that order, in double) with
///    r = sqrt(u1), w0 = 1 - r, w1 = r (1 - u2), w2 = r u2.
/// The same mesh, count and seed give the same points bit for bit wherever
/// IEEE doubles are (Python's vds.sample_surface is this call).
/// points: 3 * count doubles, x y z of each sample, mesh coordinates;
/// triangles: `count` indices into the mesh's triangles, or null. Both
/// caller-owned. Throws `InvalidMesh` ("no area to sample ...") for a mesh
/// with no triangles or none of non-zero area, and for one with an index
/// out of range or a non-finite corner.
void sampleSurface(const MeshView& mesh, std::size_t count, std::uint64_t seed, double* points,
                   std::uint32_t* triangles);

/// `sampleSurface` into vectors of their own.
struct SurfaceSamples {
    std::vector<double> points;          ///< 3 * count: x y z of each sample
    std::vector<std::uint32_t> triangles; ///< the triangle each lies on
};
SurfaceSamples sampleSurface(const MeshView& mesh, std::size_t count, std::uint64_t seed);

} // namespace vds
