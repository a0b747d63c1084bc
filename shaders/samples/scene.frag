// Samples: a model clipped and styled by solids through vds/styles.glsl
// (Trapp & Doellner 2008, Figures 1-3), with the inside test of one of:
//   SCENE_LOOKUP_VDS            the sprite's texture (vds/vpt.glsl, the include's default)
//   SCENE_LOOKUP_SLICEMAP       a slicemap pair, uniform slicing (voxel/slicemap.glsl)
//   SCENE_LOOKUP_SLICEMAP_LOCAL a slicemap pair, local slicing
//   SCENE_LOOKUP_SOLID          solid voxels (voxel/solid.glsl)
//   SCENE_LOOKUP_EXACT          the exact classifier's answers per pixel and depth layer
// or, with SCENE_PEEL, a depth-peeling pass that writes world positions for
// the exact reference. VDS_STYLE_SPRITES is defined by the host; with
// SCENE_DISTANCE (VDS lookup only) the solids' distance grids draw a band
// along clip cuts and a soft lens edge through vdsDistance (vds/vpt.glsl).
//
// Style ids (VdsBinding.style, u_baseStyle for points in no style solid):
#define SCENE_SHADED 1    // flat shading, cut surfaces (back faces) in the cut colour
#define SCENE_GOURAUD 2   // per-vertex lighting
#define SCENE_XRAY 3      // transparent: every layer darkens what is behind it (order independent)
#define SCENE_BLUEPRINT 4 // blue, with silhouettes and world-space grid lines in white

in vec3 v_world;
in vec3 v_normal;
in float v_gouraud;

#ifdef SCENE_PEEL

uniform sampler2D u_previousDepth;
uniform int u_layer;
layout(location = 0) out vec4 o_position;
layout(location = 1) out float o_depth;

void main() {
    if (u_layer > 0 && gl_FragCoord.z <= texelFetch(u_previousDepth, ivec2(gl_FragCoord.xy), 0).r) discard;
    o_position = vec4(v_world, 1.0);
    o_depth = gl_FragCoord.z;
}

#else

// Voxel lookups answer in the solid's mesh coordinates: u_toMesh[i] takes a
// world point there (the solid's placement, inverted).
// (The library resolves #include before the preprocessor runs, once per
// program, so both voxel includes come in unconditionally.)
#include "voxel/slicemap.glsl"
#include "voxel/solid.glsl"
#if defined(SCENE_LOOKUP_SLICEMAP) || defined(SCENE_LOOKUP_SLICEMAP_LOCAL)
uniform mat4 u_toMesh[VDS_STYLE_SPRITES];
uniform usampler2DArray u_slicemap[VDS_STYLE_SPRITES];
uniform VdsSlicemap u_map[VDS_STYLE_SPRITES];
#ifdef SCENE_LOOKUP_SLICEMAP_LOCAL
uniform sampler2D u_ranges[VDS_STYLE_SPRITES];
#define VDS_STYLE_INSIDE(i, p) vdsSlicemapLocalContains(u_slicemap[i], u_ranges[i], u_map[i], (u_toMesh[i] * vec4(p, 1.0)).xyz)
#else
#define VDS_STYLE_INSIDE(i, p) vdsSlicemapContains(u_slicemap[i], u_map[i], (u_toMesh[i] * vec4(p, 1.0)).xyz)
#endif
#elif defined(SCENE_LOOKUP_SOLID)
uniform mat4 u_toMesh[VDS_STYLE_SPRITES];
uniform usamplerBuffer u_voxels[VDS_STYLE_SPRITES];
uniform VdsVoxelGrid u_voxelGrid[VDS_STYLE_SPRITES];
#define VDS_STYLE_INSIDE(i, p) vdsBitGridContains(u_voxels[i], u_voxelGrid[i], (u_toMesh[i] * vec4(p, 1.0)).xyz)
#elif defined(SCENE_LOOKUP_EXACT)
// Layer k of the peeled depths and of the masks: the fragment's depth and
// its solids (bit i: solid i holds the fragment's point, by the exact classifier).
uniform sampler2DArray u_layerDepth;
uniform usampler2DArray u_layerMask;
uniform int u_layerCount;
uint g_exactMask = 0u;
uint exactMask() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    for (int k = 0; k < u_layerCount; ++k)
        if (texelFetch(u_layerDepth, ivec3(pixel, k), 0).r == gl_FragCoord.z)
            return texelFetch(u_layerMask, ivec3(pixel, k), 0).r;
    return 0u;
}
#define VDS_STYLE_INSIDE(i, p) (((g_exactMask >> uint(i)) & 1u) != 0u)
#endif

#include "vds/styles.glsl"

uniform int u_pass; // 0: opaque styles, 1: X-ray (multiplied into the opaque image)
uniform int u_baseStyle;
uniform vec3 u_viewDirection; // towards the viewer
uniform vec3 u_lightDirection;
uniform vec3 u_frontColour;
uniform vec3 u_cutColour;
uniform bool u_cutBackFaces; // back faces are cut surfaces (the scene clips); else shaded as front faces
uniform float u_gridSpacing; // blueprint grid lines, world units

#ifdef SCENE_DISTANCE
// Solid i's distance grid: world -> the mesh coordinates of its bake, the
// grid's box there, and world units per mesh unit (a uniform placement's scale).
uniform sampler3D u_distance[VDS_STYLE_SPRITES];
uniform mat4 u_distanceToMesh[VDS_STYLE_SPRITES];
uniform vec3 u_distanceLo[VDS_STYLE_SPRITES];
uniform vec3 u_distanceHi[VDS_STYLE_SPRITES];
uniform float u_distanceScale[VDS_STYLE_SPRITES];
uniform float u_distanceWidth; // world units
uniform vec3 u_bandColour;

// The signed distances of `world` to the nearest clip solid's surface (x)
// and to the lens's (y), world units; 1e30 where no such solid is on.
vec2 sceneDistances(vec3 world) {
    vec2 d = vec2(1e30);
    for (int i = 0; i < VDS_STYLE_SPRITES; ++i) {
        int role = u_vdsBinding[i].role;
        if (role == VDS_ROLE_OFF || role == VDS_ROLE_STYLE) continue;
        vec3 p = (u_distanceToMesh[i] * vec4(world, 1.0)).xyz;
        float di = u_distanceScale[i] * vdsDistance(u_distance[i], u_distanceLo[i], u_distanceHi[i], p);
        if (role == VDS_ROLE_LENS) d.y = abs(di) < abs(d.y) ? di : d.y;
        else d.x = min(d.x, abs(di));
    }
    return d;
}
#endif

layout(location = 0) out vec4 o_colour;

void main() {
    // Derivatives before any discard: they need the whole quad.
    vec3 flatNormal = normalize(cross(dFdx(v_world), dFdy(v_world)));
    vec3 cells = v_world / u_gridSpacing;
    vec3 cellWidth = fwidth(cells);
#ifdef SCENE_LOOKUP_EXACT
    g_exactMask = exactMask();
#endif
    VdsStyle s = vdsStyleAt(v_world);
    if (s.discarded) discard;
    int style = s.style == VDS_STYLE_BASE ? u_baseStyle : s.style;
    bool xray = style == SCENE_XRAY;
    if ((u_pass == 1) != xray) discard;

    float facing = abs(dot(normalize(v_normal), u_viewDirection));
#ifdef SCENE_DISTANCE
    vec2 distances = sceneDistances(v_world);
    // Lens: 0 at the border, 1 a width or more inside it (negative d) or outside it.
    float soft = clamp(abs(distances.y) / u_distanceWidth, 0.0, 1.0);
#else
    float soft = 1.0;
#endif
    if (xray) {
        float rim = 1.0 - facing;
        o_colour = vec4(mix(vec3(1.0), vec3(0.20, 0.45, 0.80), soft * (0.2 + 0.7 * rim * rim)), 1.0);
        return;
    }
    float light = 0.25 + 0.75 * abs(dot(flatNormal, u_lightDirection));
    if (!gl_FrontFacing && u_cutBackFaces) {
        o_colour = vec4(u_cutColour * light, 1.0);
        return;
    }
    vec3 colour = u_frontColour * light;
    if (style == SCENE_GOURAUD) colour = u_frontColour * v_gouraud;
    if (style == SCENE_BLUEPRINT) {
        vec3 d = abs(fract(cells - 0.5) - 0.5) / max(cellWidth, vec3(1e-6));
        float line = 1.0 - clamp(min(min(d.x, d.y), d.z), 0.0, 1.0);
        float edge = smoothstep(0.55, 0.8, 1.0 - facing);
        colour = mix(vec3(0.10, 0.22, 0.50), vec3(0.92, 0.96, 1.0), max(0.7 * line, edge));
    }
#ifdef SCENE_DISTANCE
    if (distances.x <= u_distanceWidth) colour = u_bandColour * light; // the band along a clip cut
    if (distances.y > 0.0) colour = mix(colour, vec3(0.45, 0.75, 1.0), 0.6 * (1.0 - soft)); // the lens's glow
#endif
    o_colour = vec4(colour, 1.0);
}

#endif
