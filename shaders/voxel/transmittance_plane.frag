// voxel/transmittance_plane.frag: per pixel of a receiver plane, the
// quantity in front of the receiver (surfaces, absorption or thickness) and
// the light left (see <vds/voxel/transmittance.h>). VDS_SOURCE picks the
// caster representation: 0 slicemap, 1 per-voxel absorption, 2 sprite;
// VDS_SLICEMAP_LOCAL 1 for local slicing.
#include "voxel/transmittance.glsl"

uniform vec3 u_origin; // receiver at pixel (i, j): origin + ((i + .5) / w) u + ((j + .5) / h) v
uniform vec3 u_u;
uniform vec3 u_v;
uniform vec2 u_size;
uniform mat3 u_toLight;
uniform float u_sigma;
uniform float u_extinction;

#if VDS_SOURCE == 0
uniform usampler2DArray u_slicemap;
uniform VdsSlicemap u_map;
#if VDS_SLICEMAP_LOCAL
uniform sampler2D u_ranges;
#endif
#elif VDS_SOURCE == 1
uniform sampler3D u_absorption;
uniform VdsVoxelGrid u_grid;
#else
uniform sampler3D u_ldi;
uniform VdsPlacement u_placement;
uniform float u_depthExtent; // mesh units per unit of texture depth
#endif

layout(location = 0) out vec2 o_result;

void main() {
    precise float fx = gl_FragCoord.x / u_size.x;
    precise float fy = gl_FragCoord.y / u_size.y;
    precise vec3 world = (u_origin + u_u * fx) + u_v * fy;
    vec3 p = vdsToLight(u_toLight, world);
#if VDS_SOURCE == 0
#if VDS_SLICEMAP_LOCAL
    int n = vdsSlicemapLocalSurfacesInFront(u_slicemap, u_ranges, u_map, p);
#else
    int n = vdsSlicemapSurfacesInFront(u_slicemap, u_map, p);
#endif
    o_result = vec2(float(n), n == 0 ? 1.0 : pow(1.0 - u_sigma, float(n)));
#elif VDS_SOURCE == 1
    float a = vdsAbsorptionInFront(u_absorption, u_grid, p);
    o_result = vec2(a, exp(-a));
#else
    precise float t = vdsSpriteThicknessInFront(u_ldi, u_placement, p) * u_depthExtent;
    o_result = vec2(t, exp(-u_extinction * t));
#endif
}
