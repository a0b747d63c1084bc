// voxel/refraction.frag: one ray per pixel through the solids (see
// <vds/voxel/refraction.h>). VDS_METHOD: 0 two-surface from a local
// slicemap pair, 1 two-surface from a sprite, 2 voxel march. Writes the hit
// on the background (x, y, inside length, met) and the shaded colour.
#include "voxel/refraction.glsl"

uniform vec2 u_lo;
uniform vec2 u_hi;
uniform vec2 u_size;
uniform float u_startZ;
uniform VdsRefraction u_refraction;

#if VDS_METHOD == 0
uniform usampler2DArray u_slicemap;
uniform sampler2D u_ranges;
uniform VdsSlicemap u_map;
uniform float u_columnStep;
vec4 vdsColumn(vec2 xy) { return vdsSlicemapRefractionColumn(u_slicemap, u_ranges, u_map, xy); }
#elif VDS_METHOD == 1
uniform sampler3D u_ldi;
uniform VdsPlacement u_placement;
uniform float u_depthLo;
uniform float u_depthExtent;
uniform float u_columnStep;
vec4 vdsColumn(vec2 xy) { return vdsSpriteRefractionColumn(u_ldi, u_placement, u_depthLo, u_depthExtent, xy); }
#else
uniform sampler3D u_voxels;
uniform VdsVoxelGrid u_grid;
#endif

layout(location = 0) out vec4 o_hit;
layout(location = 1) out vec4 o_colour;

#if VDS_METHOD != 2
// Two-surface refraction: enter at the front surface, travel the column's
// inside length along the refracted direction, leave through the back
// surface found there. Normals from the depths of neighbouring columns.
vec4 vdsTwoSurface(vec2 xy) {
    vec4 c = vdsColumn(xy);
    if (c.w == 0.0) return vdsToBackground(vec3(xy, u_startZ), vec3(0.0, 0.0, 1.0), 0.0, u_refraction);
    float h = u_columnStep;
    vec4 l = vdsColumn(xy - vec2(h, 0.0)), r = vdsColumn(xy + vec2(h, 0.0));
    vec4 b = vdsColumn(xy - vec2(0.0, h)), t = vdsColumn(xy + vec2(0.0, h));
    float fx = vdsDepthSlope(l.x, c.x, r.x, l.w != 0.0, r.w != 0.0, h);
    float fy = vdsDepthSlope(b.x, c.x, t.x, b.w != 0.0, t.w != 0.0, h);
    vec3 n1 = normalize(vec3(fx, fy, -1.0)); // outward: towards the viewer
    vec3 t1 = refract(vec3(0.0, 0.0, 1.0), n1, 1.0 / u_refraction.eta);
    precise vec3 p2 = vec3(xy, c.x) + t1 * c.z;
    vec4 c2 = vdsColumn(p2.xy);
    vec2 at = p2.xy;
    if (c2.w == 0.0) { // left the solid's columns: take the back surface where we entered
        c2 = c;
        at = xy;
    }
    vec4 l2 = vdsColumn(at - vec2(h, 0.0)), r2 = vdsColumn(at + vec2(h, 0.0));
    vec4 b2 = vdsColumn(at - vec2(0.0, h)), t2 = vdsColumn(at + vec2(0.0, h));
    float gx = vdsDepthSlope(l2.y, c2.y, r2.y, l2.w != 0.0, r2.w != 0.0, h);
    float gy = vdsDepthSlope(b2.y, c2.y, t2.y, b2.w != 0.0, t2.w != 0.0, h);
    vec3 n2 = normalize(vec3(-gx, -gy, 1.0)); // outward: away from the viewer
    vec3 t2dir = refract(t1, -n2, u_refraction.eta);
    if (t2dir == vec3(0.0)) t2dir = reflect(t1, -n2); // total internal reflection
    return vdsToBackground(p2, t2dir, c.z, u_refraction);
}
#endif

void main() {
    precise float fx = gl_FragCoord.x / u_size.x;
    precise float fy = gl_FragCoord.y / u_size.y;
    precise float x = u_lo.x + (u_hi.x - u_lo.x) * fx;
    precise float y = u_lo.y + (u_hi.y - u_lo.y) * fy;
#if VDS_METHOD == 2
    vec4 hit = vdsVoxelMarch(u_voxels, u_grid, vec2(x, y), u_startZ, u_refraction);
#else
    vec4 hit = vdsTwoSurface(vec2(x, y));
#endif
    o_hit = hit;
    o_colour = vec4(vdsRefractionColour(hit, u_refraction), 1.0);
}
