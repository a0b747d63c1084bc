#include <vds/gl/detail/raster_state.h>

#include <GL/glext.h>

namespace vds::detail {
namespace {

bool hasClipControl(const GlContext& gl) {
    const GlInfo& i = gl.info();
    return i.major > 4 || (i.major == 4 && i.minor >= 5);
}

} // namespace

std::string bakeDefines(const GlContext& gl) { return hasClipControl(gl) ? "#define VDS_CLIP_CONTROL\n" : ""; }

BakeRasterState::BakeRasterState(const GlContext& gl, const SpriteGrid& grid, GLuint program)
    : clipControl_(hasClipControl(gl)) {
    if (clipControl_) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glViewport(0, 0, GLsizei(grid.width), GLsizei(grid.height));
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_CLAMP);
    glFrontFace(GL_CW);
    glUseProgram(program);
    // At bake time, world = mesh coordinates: the grid's own placement.
    glUniformMatrix3fv(glGetUniformLocation(program, "u_placement.matrix"), 1, GL_FALSE, &grid.matrix[0][0]);
    glUniform3fv(glGetUniformLocation(program, "u_placement.position"), 1, &grid.position[0]);
}

BakeRasterState::~BakeRasterState() {
    if (clipControl_) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_MULTISAMPLE);
    glFrontFace(GL_CCW);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Texture makeTexture2D(GLenum format, const SpriteGrid& grid) {
    Texture t = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, format, GLsizei(grid.width), GLsizei(grid.height));
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl("allocating a bake target");
    return t;
}

} // namespace vds::detail
