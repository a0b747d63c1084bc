// voxel/refraction.glsl: refraction through closed solids in view space (the
// camera looks along +z), in front of a checkerboard plane z = backgroundZ
// (see <vds/voxel/refraction.h>). Two-surface refraction (Eisemann & Decoret
// 2006, section 3.3; Chang et al. 2014, section 5.1) reads per column the
// front depth, back depth and inside length from a local slicemap pair or a
// sprite; multiple-surface refraction marches the per-voxel normals of the
// slicing voxelization (Chang et al. 2014, section 5.2). Same arithmetic as
// the C++ references in voxel/src/refraction.cpp.
#ifndef VDS_VOXEL_REFRACTION_GLSL
#define VDS_VOXEL_REFRACTION_GLSL

#include "voxel/slicemap.glsl"
#include "vds/vpt.glsl"

struct VdsRefraction {
    float eta;         // refractive index inside (outside 1)
    float absorption;  // per unit length inside, red; green 0.35x, blue 0.2x
    float frost;       // background blur width per unit length inside
    float checker;     // checkerboard square size
    float backgroundZ; // the checkerboard plane
    int maxSteps;      // voxel march limit
};

// Integral from 0 to x of the square wave +1 on [0, 1), -1 on [1, 2), period 2.
float vdsSquareWaveIntegral(float x) {
    precise float m = x - 2.0 * floor(x * 0.5);
    return 1.0 - abs(1.0 - m);
}

// The square wave box-filtered over width w around x.
float vdsFilteredSquareWave(float x, float w) {
    if (!(w > 1e-4)) {
        precise float m = x - 2.0 * floor(x * 0.5);
        return m < 1.0 ? 1.0 : -1.0;
    }
    precise float a = vdsSquareWaveIntegral(x + 0.5 * w) - vdsSquareWaveIntegral(x - 0.5 * w);
    return a / w;
}

// hit: (x, y) on the background, length inside, 1 if the background was met.
vec3 vdsRefractionColour(vec4 hit, VdsRefraction r) {
    if (hit.w == 0.0) return vec3(0.0);
    precise float w = r.frost * hit.z / r.checker;
    float a = vdsFilteredSquareWave(hit.x / r.checker, w) * vdsFilteredSquareWave(hit.y / r.checker, w);
    vec3 background = mix(vec3(0.2, 0.25, 0.35), vec3(0.95, 0.92, 0.85), 0.5 + 0.5 * a);
    return background * exp(-r.absorption * hit.z * vec3(1.0, 0.35, 0.2));
}

vec4 vdsToBackground(vec3 p, vec3 d, float insideLength, VdsRefraction r) {
    if (!(d.z > 0.0)) return vec4(0.0, 0.0, insideLength, 0.0);
    precise float t = (r.backgroundZ - p.z) / d.z;
    precise vec2 xy = p.xy + d.xy * t;
    return vec4(xy, insideLength, 1.0);
}

// Slope of a depth across one axis from the columns at -h, 0, +h (central
// where both neighbours hold solid, one-sided where one does, else 0).
float vdsDepthSlope(float minus, float centre, float plus, bool hasMinus, bool hasPlus, float h) {
    if (hasMinus && hasPlus) return (plus - minus) / (2.0 * h);
    if (hasPlus) return (plus - centre) / h;
    if (hasMinus) return (centre - minus) / h;
    return 0.0;
}

// ---- Columns: (front z, back z, inside length, 1 if the column holds solid).

// The inner slices of a slicemap column by the inner-voxel rule, in one pass
// from near to far (E&D 2006, section 3.3: incremental; empty slices after an
// ambiguous one wait for the next boundary slice).
int vdsSlicemapInnerSlices(usampler2DArray maps, VdsSlicemap map, ivec2 column) {
    int words = map.grid.size.z >> 5;
    int inner = 0, pending = 0, state = 0; // 0 outside, 1 inside, 2 after an ambiguous slice
    for (int w = 0; w < words; ++w) {
        uint f = vdsSlicemapWord(maps, column, 0, w);
        uint b = vdsSlicemapWord(maps, column, map.backLayer, w);
        for (int k = 0; k < 32; ++k) {
            bool front = ((f >> uint(k)) & 1u) != 0u, back = ((b >> uint(k)) & 1u) != 0u;
            if (front || back) {
                if (state == 2 && back && !front) inner += pending;
                pending = 0;
                inner += 1;
                state = front && back ? 2 : (front ? 1 : 0);
            } else if (state == 1) {
                inner += 1;
            } else if (state == 2) {
                pending += 1;
            }
        }
    }
    return inner;
}

vec4 vdsSlicemapRefractionColumn(usampler2DArray maps, sampler2D ranges, VdsSlicemap map, vec2 xy) {
    vec3 v = vdsToCells(map.grid, vec3(xy, map.grid.origin.z));
    ivec2 column;
    if (!vdsSlicemapColumn(map, v, column)) return vec4(0.0);
    vec3 range = texelFetch(ranges, column, 0).xyz;
    if (!(range.x <= range.y)) return vec4(0.0);
    int inner = vdsSlicemapInnerSlices(maps, map, column);
    precise float front = map.grid.origin.z + range.x / map.grid.scale.z;
    precise float back = map.grid.origin.z + range.y / map.grid.scale.z;
    precise float sliceLength = range.z > 0.0 ? 1.0 / (range.z * map.grid.scale.z) : 0.0;
    return vec4(front, back, float(inner) * sliceLength, 1.0);
}

// A sprite baked along z whose box starts at depthLo and is depthExtent deep.
vec4 vdsSpriteRefractionColumn(sampler3D ldi, VdsPlacement placement, float depthLo, float depthExtent, vec2 xy) {
    vec3 T = vdsToTexture(placement, vec3(xy, depthLo));
    ivec3 size = textureSize(ldi, 0);
    precise float fs = floor(T.x * float(size.x));
    precise float ft = floor(T.y * float(size.y));
    if (!(fs >= 0.0 && fs < float(size.x) && ft >= 0.0 && ft < float(size.y))) return vec4(0.0);
    ivec2 column = ivec2(fs, ft);
    int winding = 0, parity = 0;
    float entry = 0.0, first = -1.0, last = 0.0;
    precise float t = 0.0;
    for (int k = 0; k < size.z; ++k) {
        float e = texelFetch(ldi, ivec3(column, k), 0).r;
        int before = winding;
        // The whole column (every crossing lies in front of depth 2), up to
        // the padding (an entering crossing at depth 1 bounds nothing).
        if (e == 1.0 || !vdsCountCrossing(e, 2.0, parity, winding)) break;
        float d = abs(e);
        if (before == 0 && winding != 0) {
            entry = d;
            if (first < 0.0) first = d;
        } else if (before != 0 && winding == 0) {
            t += d - entry;
            last = d;
        }
    }
    if (first < 0.0) return vec4(0.0);
    precise float front = depthLo + first * depthExtent;
    precise float back = depthLo + last * depthExtent;
    precise float inside = t * depthExtent;
    return vec4(front, back, inside, 1.0);
}

// ---- Multiple-surface refraction by marching voxels.

// `voxels`: RGBA32F 3D texture over `grid`, (sum of unit normals, fragments).
vec4 vdsVoxelMarch(sampler3D voxels, VdsVoxelGrid grid, vec2 xy, float startZ, VdsRefraction r) {
    vec3 p = vec3(xy, max(startZ, grid.origin.z));
    vec3 d = vec3(0.0, 0.0, 1.0);
    precise float stepLength = 0.5 / grid.scale.x;
    bool inside = false;
    precise float insideLength = 0.0;
    for (int s = 0; s < r.maxSteps; ++s) {
        vec3 v = vdsToCells(grid, p);
        vec3 f = floor(v);
        if (!(f.x >= 0.0 && f.y >= 0.0 && f.z >= 0.0 && f.x < float(grid.size.x) && f.y < float(grid.size.y) &&
              f.z < float(grid.size.z)))
            return vdsToBackground(p, d, insideLength, r);
        vec4 voxel = texelFetch(voxels, ivec3(f), 0);
        float len = length(voxel.xyz);
        if (voxel.w > 0.0 && len > 1e-6) {
            vec3 n = voxel.xyz / len;
            float c = dot(d, n);
            if (!inside && c < 0.0) {
                d = refract(d, n, 1.0 / r.eta);
                inside = true;
            } else if (inside && c > 0.0) {
                vec3 out_ = refract(d, -n, r.eta);
                if (out_ == vec3(0.0)) {
                    d = reflect(d, -n); // total internal reflection
                } else {
                    d = out_;
                    inside = false;
                }
            }
        }
        p += d * stepLength;
        if (inside) insideLength += stepLength;
    }
    return vec4(0.0, 0.0, insideLength, 0.0);
}

#endif
