// A sprite's columns (CSR) into the paper's 3D texture (Trapp & Doellner
// 2008, section 4.1, step 2): crossing k of column (i, j) becomes texel
// (i, j, k); the texture was cleared to 1.0, the padding. The texture is R32F,
// written through an r32ui view so that every bit is kept as stored.
layout(local_size_x = 256) in; // before the include: it reads gl_WorkGroupSize
#include "vds/compute.glsl"

layout(std430, binding = 0) readonly restrict buffer Offsets { uint offsets[]; };
layout(std430, binding = 1) readonly restrict buffer Crossings { uint crossings[]; };
layout(binding = 0, r32ui) writeonly restrict uniform uimage3D u_ldi;
uniform uint u_columns;  // in this band
uniform uint u_width;
uniform int u_rowBegin;
uniform uint u_base;     // the band's first offset

void main() {
    for (uint c = gl_GlobalInvocationID.x; c < u_columns; c = vdsNextIndex(c, u_columns)) {
        ivec2 texel = ivec2(int(c % u_width), int(c / u_width) + u_rowBegin);
        uint begin = offsets[c] - u_base, end = offsets[c + 1u] - u_base;
        for (uint k = begin; k < end; ++k) imageStore(u_ldi, ivec3(texel, int(k - begin)), uvec4(crossings[k], 0u, 0u, 0u));
    }
}
