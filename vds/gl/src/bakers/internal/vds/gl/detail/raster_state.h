// vds::gl internal: what the GL bakers' raster passes share (raster_state.cpp):
// the crossing keys of the bake shaders, their defines, the raster state of
// a pass, and its 2D targets.
#pragma once

#include <cstdint>
#include <string>

#include <GL/gl.h>

#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/sprite.h>

namespace vds::detail {

constexpr std::uint32_t kEnteringBit = 0x80000000u;
constexpr std::uint32_t kNoNode = 0xffffffffu;

/// A crossing as the bake shaders key it: the entering bit beside the triangle index.
inline float encodeKeyed(float depth, std::uint32_t key) { return encodeCrossing(depth, (key & kEnteringBit) != 0); }

/// "#define VDS_CLIP_CONTROL" where the context has glClipControl (GL 4.5).
std::string bakeDefines(const GlContext& gl);

/// The raster state of a bake pass, set for the scope and put back to GL's
/// defaults when it ends, also when the pass throws: clip control [0,1] depth,
/// viewport = the grid, no culling, blending or multisampling, depth clamping
/// (crossings on the box's near and far faces must not be clipped), front
/// faces clockwise (the view keeps handedness: clockwise = normal towards the
/// viewer = entering), `program` in use with the grid's placement uniform.
class BakeRasterState {
public:
    BakeRasterState(const GlContext& gl, const SpriteGrid& grid, GLuint program);
    ~BakeRasterState();
    BakeRasterState(const BakeRasterState&) = delete;
    BakeRasterState& operator=(const BakeRasterState&) = delete;

private:
    bool clipControl_;
};

/// A width x height single-level 2D texture of `format`, nearest filtering.
Texture makeTexture2D(GLenum format, const SpriteGrid& grid);

} // namespace vds::detail
