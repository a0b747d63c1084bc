// vds/styles.glsl: clipping, 3D magic lenses and styles bound to solids, in
// one call per fragment (Trapp & Doellner 2008, section 4 and Figures 1-3).
//
// Up to VDS_STYLE_SPRITES solids (default 8) are tested against a fragment's
// world position in one pass. Each solid carries a role:
//   VDS_ROLE_OFF        ignored
//   VDS_ROLE_CLIP_AWAY  fragments inside the clip-away region are discarded
//   VDS_ROLE_CLIP_TO    fragments outside the clip-to region are discarded
//                       (only the inside of the solid is kept)
//   VDS_ROLE_STYLE      fragments inside get the solid's style id
//   VDS_ROLE_LENS       the same, but a lens wins over every style solid
//                       (a 3D magic lens moved over styled space)
// The clip-away region is the union or the intersection of the clip-away
// solids (VDS_COMBINE_UNION / VDS_COMBINE_INTERSECTION), the clip-to region
// likewise of the clip-to solids; each role has its own combine mode. Among
// style solids the one with the highest index that holds the point wins,
// then among lenses likewise; a point in none gets VDS_STYLE_BASE (0).
//
// Usage, with the VDS lookup of vds/vpt.glsl (any stage, GLSL 4.30+):
//   #define VDS_STYLE_SPRITES 3          // optional, before the include
//   #include "vds/styles.glsl"
//   ...
//   VdsStyle s = vdsStyleAt(worldPosition);
//   if (s.discarded) discard;
//   if (s.style == 2) ... // blueprint, X-ray, whatever style 2 means to you
// Uniforms the include declares (set them from the host):
//   int           u_vdsSpriteCount           solids in use, 0..VDS_STYLE_SPRITES
//   VdsBinding    u_vdsBinding[i]            .role, .style, .rule (VDS_RULE_*) of solid i
//   int           u_vdsCombineAway, u_vdsCombineTo   VDS_COMBINE_* (default 0: union)
//   sampler3D     u_vdsLdi[i]                sprite i's texture  } GpuSprite::setUniforms(program,
//   VdsPlacement  u_vdsPlacement[i]          sprite i's placement } "u_vdsLdi[i]", "u_vdsPlacement[i]", unit)
// From C++, vds::setStyleUniforms (<vds/gl/styles.h>) sets all of these, with
// the roles as vds::StyleRole and the sprites on texture units from a base
// unit the caller picks; it points the unused slots' samplers there too, so
// that they never share unit 0 with the application's own samplers.
// Moving a solid (a lens along a path) is a new placement: Sprite::transform
// or GpuSprite::setPlacement, no re-bake.
//
// Other representations: define VDS_STYLE_INSIDE(i, p) before the include
// as an expression that is true when solid i holds world point p (i is a
// dynamically uniform int, p a vec3); the sampler and placement uniforms are
// then not declared. For example, with solid voxels (shaders/voxel/solid.glsl):
//   uniform usamplerBuffer u_voxels[3]; uniform VdsVoxelGrid u_grid[3];
//   #define VDS_STYLE_INSIDE(i, p) vdsBitGridContains(u_voxels[i], u_grid[i], p)
// The samples (samples/common/scene.cpp, shaders/samples/scene.frag) do this
// for slicemaps, solid voxels and an exact per-pixel mask.
#ifndef VDS_STYLES_GLSL
#define VDS_STYLES_GLSL

#include "vds/vpt.glsl"

#ifndef VDS_STYLE_SPRITES
#define VDS_STYLE_SPRITES 8
#endif

#define VDS_ROLE_OFF 0
#define VDS_ROLE_CLIP_AWAY 1
#define VDS_ROLE_CLIP_TO 2
#define VDS_ROLE_STYLE 3
#define VDS_ROLE_LENS 4

#define VDS_COMBINE_UNION 0
#define VDS_COMBINE_INTERSECTION 1

#define VDS_STYLE_BASE 0

struct VdsBinding {
    int role;  // VDS_ROLE_*
    int style; // style id given to points inside (style and lens roles)
    int rule;  // VDS_RULE_PARITY or VDS_RULE_WINDING (the VDS lookup only)
};

uniform int u_vdsSpriteCount;
uniform VdsBinding u_vdsBinding[VDS_STYLE_SPRITES];
uniform int u_vdsCombineAway;
uniform int u_vdsCombineTo;

#ifndef VDS_STYLE_INSIDE
uniform sampler3D u_vdsLdi[VDS_STYLE_SPRITES];
uniform VdsPlacement u_vdsPlacement[VDS_STYLE_SPRITES];
#define VDS_STYLE_INSIDE(i, p) vdsContains(u_vdsLdi[i], u_vdsPlacement[i], p, u_vdsBinding[i].rule)
#endif

// What vdsStyleAt decides for one point.
struct VdsStyle {
    bool discarded; // clipped: inside the clip-away region or outside the clip-to region
    int style;      // style id (VDS_STYLE_BASE where no style or lens solid holds the point)
    int sprite;     // the solid that gave the style, -1 for the base style
    uint inside;    // bit i set iff solid i (of any role but off) holds the point
};

// Union: any member holds the point; intersection: every member does. An
// empty set of members is an empty region.
bool vdsCombine(uint inside, uint members, int combine) {
    if (members == 0u) return false;
    return combine == VDS_COMBINE_INTERSECTION ? (inside & members) == members : (inside & members) != 0u;
}

VdsStyle vdsStyleAt(vec3 world) {
    VdsStyle s;
    s.inside = 0u;
    s.style = VDS_STYLE_BASE;
    s.sprite = -1;
    uint away = 0u, to = 0u;
    int lens = -1;
    int count = min(u_vdsSpriteCount, VDS_STYLE_SPRITES);
    for (int i = 0; i < count; ++i) {
        int role = u_vdsBinding[i].role;
        if (role == VDS_ROLE_OFF) continue;
        uint bit = 1u << uint(i);
        if (role == VDS_ROLE_CLIP_AWAY) away |= bit;
        if (role == VDS_ROLE_CLIP_TO) to |= bit;
        if (!(VDS_STYLE_INSIDE(i, world))) continue;
        s.inside |= bit;
        if (role == VDS_ROLE_STYLE && lens < 0) {
            s.style = u_vdsBinding[i].style;
            s.sprite = i;
        }
        if (role == VDS_ROLE_LENS) {
            lens = i;
            s.style = u_vdsBinding[i].style;
            s.sprite = i;
        }
    }
    s.discarded = vdsCombine(s.inside, away, u_vdsCombineAway) ||
                  (to != 0u && !vdsCombine(s.inside, to, u_vdsCombineTo));
    return s;
}

#endif
