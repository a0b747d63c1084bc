// The points of a classify program, four at a time: a buffer of tightly
// packed vec3 (12 bytes a point, glm::vec3 and CUDA float3 arrays) read as
// three aligned vec4 per group of four, as floats for the tail. Declares the
// buffers at bindings 0 (as vec4) and 1 (as float), both over the same
// range, and the point count `u_count`.
#ifndef VDS_POINTS_GLSL
#define VDS_POINTS_GLSL

layout(std430, binding = 0) readonly buffer Points4 { vec4 points4[]; };
layout(std430, binding = 1) readonly buffer Points { float points[]; };
uniform uint u_count;

// Groups of four points, the last one partial: ceil(u_count / 4).
uint vdsPointQuads() { return u_count / 4u + (u_count % 4u != 0u ? 1u : 0u); }

// Group q's points (q < vdsPointQuads()) and how many of them are real; the
// tail group repeats its last real point.
uint vdsLoadPoints(uint q, out vec3 p[4]) {
    uint first = 4u * q;
    uint valid = min(u_count - first, 4u);
    if (valid == 4u) {
        vec4 a = points4[3u * q], b = points4[3u * q + 1u], c = points4[3u * q + 2u];
        p[0] = a.xyz;
        p[1] = vec3(a.w, b.xy);
        p[2] = vec3(b.zw, c.x);
        p[3] = c.yzw;
    } else {
        for (uint k = 0u; k < 4u; ++k) {
            uint i = 3u * (first + min(k, valid - 1u));
            p[k] = vec3(points[i], points[i + 1u], points[i + 2u]);
        }
    }
    return valid;
}

#endif
