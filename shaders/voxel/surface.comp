// Conservative surface voxelization, one invocation per triangle (Schwarz
// 2012, section 2.4; Schwarz & Seidel 2010). Coordinates are integers in
// units of 1/256 cell, held in doubles: voxel (x, y, z) is the box
// [256 x, 256 (x + 1)] x ... ; closed sets, touching counts as overlap.
#include "voxel/grid.glsl"
#include "voxel/triangles.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 2) coherent buffer VdsVoxels { uint vdsVoxels[]; };
uniform VdsVoxelGrid u_grid;
uniform uint u_triangleCount;

const double kCell = 256.0;

dvec3 vdsFixedCells(vec3 world) {
    vec3 v = vdsToCells(u_grid, world);
    return dvec3(floor(v * 256.0 + 0.5));
}

// Edge normals (pointing inside) and offsets of one 2D projection, so that a
// box with min corner b overlaps the projected triangle's half-plane of edge i
// iff dot(m[i], b) + g[i] >= 0 (critical corner folded into g).
struct Projection {
    dvec2 m[3];
    double g[3];
};

Projection vdsProjection(dvec2 w0, dvec2 w1, dvec2 w2, double normalComponent) {
    Projection p;
    dvec2 w[3] = dvec2[3](w0, w1, w2);
    double orientation = normalComponent > 0.0 ? 1.0 : -1.0;
    for (int i = 0; i < 3; ++i) {
        dvec2 a = w[i], b = w[(i + 1) % 3];
        precise dvec2 m = dvec2(a.y - b.y, b.x - a.x) * orientation;
        dvec2 f = dvec2(m.x > 0.0 ? kCell : 0.0, m.y > 0.0 ? kCell : 0.0);
        precise double g = m.x * (f.x - a.x) + m.y * (f.y - a.y);
        p.m[i] = m;
        p.g[i] = g;
    }
    return p;
}

bool vdsOverlaps2D(Projection p, dvec2 b) {
    for (int i = 0; i < 3; ++i) {
        precise double e = p.m[i].x * b.x + p.m[i].y * b.y + p.g[i];
        if (e < 0.0) return false;
    }
    return true;
}

void main() {
    uint t = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
    if (t >= u_triangleCount) return;
    dvec3 v0 = vdsFixedCells(vdsTriangleVertex(t, 0u));
    dvec3 v1 = vdsFixedCells(vdsTriangleVertex(t, 1u));
    dvec3 v2 = vdsFixedCells(vdsTriangleVertex(t, 2u));
    dvec3 lo = min(v0, min(v1, v2)), hi = max(v0, max(v1, v2));
    // Voxels touching the bounding box, clipped to the grid.
    ivec3 first = max(ivec3(ceil(lo / kCell)) - 1, ivec3(0));
    ivec3 last = min(ivec3(floor(hi / kCell)), u_grid.size - 1);
    if (any(greaterThan(first, last))) return;

    precise dvec3 e1 = v1 - v0, e2 = v2 - v0;
    precise dvec3 n = dvec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    dvec3 c1 = dvec3(n.x > 0.0 ? kCell : 0.0, n.y > 0.0 ? kCell : 0.0, n.z > 0.0 ? kCell : 0.0);
    dvec3 c2 = dvec3(kCell) - c1;
    Projection xy = vdsProjection(v0.xy, v1.xy, v2.xy, n.z);
    Projection yz = vdsProjection(v0.yz, v1.yz, v2.yz, n.x);
    Projection zx = vdsProjection(v0.zx, v1.zx, v2.zx, n.y);

    // The axis the triangle faces most: columns along it hold at most a few
    // candidates each (the plane's range over the column). A triangle of zero
    // area has n = 0: every voxel of its box is a candidate.
    dvec3 an = abs(n);
    int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    int u = (axis + 1) % 3, w = (axis + 2) % 3;
    bool degenerate = an[axis] == 0.0;
    for (int i = first[u]; i <= last[u]; ++i) {
        for (int j = first[w]; j <= last[w]; ++j) {
            int k0 = first[axis], k1 = last[axis];
            if (!degenerate) {
                // Plane coordinate along `axis` at the column's corners, rounded: widened by a cell.
                // (No "infinite" start value: 1e300 is no float literal, and GLSL needs the lf suffix.)
                double lowest = 0.0lf, highest = 0.0lf;
                for (int corner = 0; corner < 4; ++corner) {
                    double cu = double(i + (corner & 1)) * kCell, cw = double(j + (corner >> 1)) * kCell;
                    double h = v0[axis] - (n[u] * (cu - v0[u]) + n[w] * (cw - v0[w])) / n[axis];
                    lowest = corner == 0 ? h : min(lowest, h);
                    highest = corner == 0 ? h : max(highest, h);
                }
                k0 = max(k0, int(floor(lowest / kCell)) - 1);
                k1 = min(k1, int(floor(highest / kCell)) + 1);
            }
            for (int k = k0; k <= k1; ++k) {
                ivec3 cell;
                cell[axis] = k;
                cell[u] = i;
                cell[w] = j;
                dvec3 p = dvec3(cell) * kCell;
                // Plane: the two critical corners on different sides (or one on it).
                precise double s1 = dot(n, p + c1 - v0);
                precise double s2 = dot(n, p + c2 - v0);
                if ((s1 > 0.0 && s2 > 0.0) || (s1 < 0.0 && s2 < 0.0)) continue;
                if (!vdsOverlaps2D(xy, p.xy) || !vdsOverlaps2D(yz, p.yz) || !vdsOverlaps2D(zx, p.zx)) continue;
                atomicOr(vdsVoxels[vdsWordIndex(u_grid.size, cell)], 1u << uint(cell.z & 31));
            }
        }
    }
}
