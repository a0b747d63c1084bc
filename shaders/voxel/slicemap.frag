// Slicemap pass (Eisemann & Decoret 2006, section 2.2): each fragment turns
// its depth (the slice coordinate, see voxel/raster.vert) into a one-bit
// slice mask, ORed into the RGBA32UI targets by
// glLogicOp(GL_OR). Slice s is bit s % 32 of channel (s / 32) % 4 of target
// s / 128. Front-facing fragments (the ray towards +z enters) go to the
// front map, back-facing ones to the back map (section 3.3): both in one pass
// (front targets first, then back targets) when u_facing is 0, else only the
// facing u_facing names (1 front, 2 back) into the bound targets.
// Defines: VDS_SLICEMAP_TARGETS (targets per map), VDS_SLICEMAP_OUTPUTS
// (targets bound), VDS_SLICEMAP_LOCAL (per-column ranges from the first pass).
in float v_depth;
uniform int u_slices;
uniform int u_facing;
#ifdef VDS_SLICEMAP_LOCAL
uniform sampler2D u_near;
uniform sampler2D u_far;
#endif
layout(location = 0) out uvec4 o_targets[VDS_SLICEMAP_OUTPUTS];

void main() {
    if ((u_facing == 1 && !gl_FrontFacing) || (u_facing == 2 && gl_FrontFacing)) discard;
#ifdef VDS_SLICEMAP_LOCAL
    ivec2 column = ivec2(gl_FragCoord.xy);
    float near = texelFetch(u_near, column, 0).r;
    float far = texelFetch(u_far, column, 0).r;
    float perDepth = far > near ? float(u_slices) / (far - near) : 0.0;
    precise float s = floor((v_depth - near) * perDepth);
#else
    float s = floor(v_depth);
#endif
    int slice = clamp(int(s), 0, u_slices - 1);
    int target = (u_facing == 0 && !gl_FrontFacing ? VDS_SLICEMAP_TARGETS : 0) + (slice >> 7);
    uvec4 mask = uvec4(0u);
    mask[(slice >> 5) & 3] = 1u << uint(slice & 31);
    for (int t = 0; t < VDS_SLICEMAP_OUTPUTS; ++t) o_targets[t] = t == target ? mask : uvec4(0u);
}
