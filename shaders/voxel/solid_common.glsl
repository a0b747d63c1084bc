// voxel/solid_common.glsl: what the two solid voxelizers share (Schwarz,
// "Practical Binary Surface and Solid Voxelization with Direct3D 11", GPU
// Pro 3, 2012, sections 2.3 and 2.5).
//
// Triangles are taken in cell coordinates with x and y snapped to 1/256 of a
// cell (exactly what the rasterizer sees, see voxel/raster.vert), so every
// edge function below is exact in double precision: coordinates are
// multiples of 2^-8 below 2^15, a product of two differences needs at most
// 46 bits. The depth of a triangle's plane at a column centre is computed by
// the same function in the fragment shader of the rasterizing voxelizer and
// in the compute voxelizer, so both flip the same voxels.
//
// A voxel is flipped by a triangle when the triangle covers its column
// centre and lies strictly in front of its centre (smaller z): the ray from
// the centre towards -z crosses it, the convention of vds::ExactClassifier.
#ifndef VDS_VOXEL_SOLID_COMMON_GLSL
#define VDS_VOXEL_SOLID_COMMON_GLSL

#include "voxel/grid.glsl"
#include "voxel/triangles.glsl"

// Triangle t in cell coordinates, x and y snapped.
void vdsSnappedTriangle(VdsVoxelGrid grid, uint t, out vec3 a, out vec3 b, out vec3 c) {
    vec3 v[3];
    for (uint k = 0u; k < 3u; ++k) {
        vec3 p = vdsToCells(grid, vdsTriangleVertex(t, k));
        v[k] = vec3(vdsSnapToSubcells(p.x), vdsSnapToSubcells(p.y), p.z);
    }
    a = v[0];
    b = v[1];
    c = v[2];
}

// Twice the signed area of (a, b, q) in xy, exactly: > 0 when q lies to the
// left of a -> b.
double vdsEdge(vec3 a, vec3 b, dvec2 q) {
    precise double ex = double(b.x) - double(a.x);
    precise double ey = double(b.y) - double(a.y);
    precise double e = ex * (q.y - double(a.y)) - ey * (q.x - double(a.x));
    return e;
}

// Whether the counter-clockwise triangle (a, b, c) claims the point q under
// the fill rule of the rasterizer (Schwarz 2012, figure 2.9): a point on an
// edge belongs to the triangle iff the edge is a left edge (running towards
// -y, y up) or a horizontal bottom edge (running towards +x, the interior
// above it): Direct3D's top-left rule with window y pointing down, which is
// also what llvmpipe applies to GL framebuffer objects (y up). A point on an
// edge shared by two triangles is thus claimed by exactly one of them.
bool vdsClaimsEdge(vec3 a, vec3 b, dvec2 q) {
    double e = vdsEdge(a, b, q);
    return e > 0.0 || (e == 0.0 && (b.y < a.y || (b.y == a.y && b.x > a.x)));
}
bool vdsCovers(vec3 a, vec3 b, vec3 c, dvec2 q) {
    return vdsClaimsEdge(a, b, q) && vdsClaimsEdge(b, c, q) && vdsClaimsEdge(c, a, q);
}

// Depth (cell z) of the plane through a, b, c at the column point q, from
// exact barycentric weights. The triangle must not be parallel to z.
double vdsPlaneDepth(vec3 a, vec3 b, vec3 c, dvec2 q) {
    precise double wa = vdsEdge(b, c, q);
    precise double wb = vdsEdge(c, a, q);
    precise double wc = vdsEdge(a, b, q);
    precise double z = (wa * double(a.z) + wb * double(b.z) + wc * double(c.z)) / (wa + wb + wc);
    return z;
}

// The first voxel of a column whose centre k + 0.5 lies strictly behind depth z.
int vdsFirstVoxelBehind(double z) { return max(int(floor(z - 0.5)) + 1, 0); }

// Bits of word `word` of a column that hold cells (bits past size.z are 0).
uint vdsValidBits(ivec3 size, int word) {
    int valid = size.z - 32 * word;
    return valid >= 32 ? 0xffffffffu : ((1u << uint(valid)) - 1u);
}

#endif
