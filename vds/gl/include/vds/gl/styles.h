// vds: the host side of shaders/vds/styles.glsl (clipping, 3D magic lenses
// and styles bound to solids): its role and combine constants as C++
// enums, and one call that sets its uniforms on texture units the caller
// chooses.
#pragma once

#include <cstdint>
#include <vector>

#include <vds/classify.h>
#include <vds/gl/sprite.h>

namespace vds {

/// What a solid does in styles.glsl: the values of its VDS_ROLE_* constants.
enum class StyleRole : std::int32_t {
    Off = 0,      ///< VDS_ROLE_OFF: ignored
    ClipAway = 1, ///< VDS_ROLE_CLIP_AWAY: fragments inside the clip-away region are discarded
    ClipTo = 2,   ///< VDS_ROLE_CLIP_TO: fragments outside the clip-to region are discarded
    Style = 3,    ///< VDS_ROLE_STYLE: fragments inside get the solid's style id
    Lens = 4,     ///< VDS_ROLE_LENS: the same, winning over every style solid
};

/// How the solids of one clip role combine: VDS_COMBINE_*.
enum class StyleCombine : std::int32_t { Union = 0, Intersection = 1 };

/// One solid of styles.glsl: slot i of the shader's arrays.
struct StyleSolid {
    /// Its sprite (sampler u_vdsLdi[i], placement u_vdsPlacement[i]); null
    /// when the shader defines VDS_STYLE_INSIDE and samples its own.
    const GpuSprite* sprite = nullptr;
    StyleRole role = StyleRole::Off;
    std::int32_t style = 0; ///< style id given to points inside (Style and Lens)
    Rule rule = Rule::Parity; ///< Parity or Winding (styles.glsl reads no boundary)
};

struct StyleOptions {
    /// Solid i's sprite goes on texture unit baseUnit + i: choose units
    /// your own samplers do not use.
    std::uint32_t baseUnit = 0;
    /// The shader's VDS_STYLE_SPRITES (8 unless defined before the include).
    std::uint32_t slots = 8;
    StyleCombine combineAway = StyleCombine::Union;
    StyleCombine combineTo = StyleCombine::Union;
};

/// Sets every uniform styles.glsl declares in `program` (with
/// glProgramUniform: the program need not be in use) and binds solid i's
/// sprite texture to unit `baseUnit + i`. The slots past `solids.size()`
/// are switched off and their samplers pointed at `baseUnit` too, a
/// sampler3D unit: GL refuses a draw where two samplers of different types
/// share a unit, so unused slots must not stay on unit 0, where the
/// application's own sampler2D may be. Returns the first unit after those
/// used (baseUnit + solids.size()). Throws `InvalidArgument` for more
/// solids than `slots` or Rule::GeneralizedWinding, and `GlError` (one
/// line) for a sprite of another context or thread. Leaves no GL error.
std::uint32_t setStyleUniforms(GLuint program, const std::vector<StyleSolid>& solids, const StyleOptions& options = {});

} // namespace vds
