#include <vds/gl/styles.h>

#include <string>

#include <GL/glext.h>

#include <vds/error.h>

namespace vds {

std::uint32_t setStyleUniforms(GLuint program, const std::vector<StyleSolid>& solids, const StyleOptions& options) {
    if (solids.size() > options.slots)
        throw InvalidArgument("setStyleUniforms: " + std::to_string(solids.size()) + " solids for " +
                              std::to_string(options.slots) + " slots (define VDS_STYLE_SPRITES before the include)");
    auto at = [program](const std::string& name) { return glGetUniformLocation(program, name.c_str()); };
    glProgramUniform1i(program, at("u_vdsSpriteCount"), GLint(solids.size()));
    glProgramUniform1i(program, at("u_vdsCombineAway"), GLint(options.combineAway));
    glProgramUniform1i(program, at("u_vdsCombineTo"), GLint(options.combineTo));
    for (std::uint32_t i = 0; i < options.slots; ++i) {
        const std::string k = "[" + std::to_string(i) + "]";
        const GLuint unit = options.baseUnit + (i < solids.size() ? i : 0);
        if (i >= solids.size()) {
            glProgramUniform1i(program, at("u_vdsBinding" + k + ".role"), GLint(StyleRole::Off));
            glProgramUniform1i(program, at("u_vdsLdi" + k), GLint(options.baseUnit));
            continue;
        }
        const StyleSolid& solid = solids[i];
        if (solid.rule == Rule::GeneralizedWinding)
            throw InvalidArgument("setStyleUniforms: styles.glsl answers Rule::Parity and Rule::Winding, not the "
                                  "generalized winding number");
        glProgramUniform1i(program, at("u_vdsBinding" + k + ".role"), GLint(solid.role));
        glProgramUniform1i(program, at("u_vdsBinding" + k + ".style"), solid.style);
        glProgramUniform1i(program, at("u_vdsBinding" + k + ".rule"), solid.rule == Rule::Winding ? 1 : 0);
        if (solid.sprite) solid.sprite->setUniforms(program, "u_vdsLdi" + k, "u_vdsPlacement" + k, unit);
        else glProgramUniform1i(program, at("u_vdsLdi" + k), GLint(options.baseUnit));
    }
    checkGl("setStyleUniforms");
    return options.baseUnit + std::uint32_t(solids.size());
}

} // namespace vds
