// The host side of styles.glsl (<vds/gl/styles.h>): the C++ role and
// combine values are the shader's, and the default 8 slots with fewer
// solids run beside the application's own sampler2D on unit 0.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include <vds/bake.h>
#include <vds/error.h>
#include <vds/gl/shader.h>
#include <vds/gl/styles.h>

#include "../support/gl_fixture.h"
#include "solids.h"

namespace vds {
namespace {

using StyleBindingTest = test::GlTest;

std::vector<std::int32_t> run(const Program& program, std::size_t words) {
    Buffer out = Buffer::create();
    std::vector<std::int32_t> values(words, -7);
    glNamedBufferStorage(out.id(), GLsizeiptr(words * 4), values.data(), GL_DYNAMIC_STORAGE_BIT);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(words * 4), values.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glUseProgram(0);
    return values;
}

TEST_F(StyleBindingTest, TheHostConstantsAreTheShaders) {
    const Program program = buildProgram({{GL_COMPUTE_SHADER, "roles.comp",
                                           "#include \"vds/styles.glsl\"\nlayout(local_size_x = 1) in;\n"
                                           "layout(std430, binding = 0) buffer B { int v[8]; };\n"
                                           "void main() { v[0] = VDS_ROLE_OFF; v[1] = VDS_ROLE_CLIP_AWAY; v[2] = VDS_ROLE_CLIP_TO;\n"
                                           "  v[3] = VDS_ROLE_STYLE; v[4] = VDS_ROLE_LENS; v[5] = VDS_COMBINE_UNION;\n"
                                           "  v[6] = VDS_COMBINE_INTERSECTION; v[7] = VDS_STYLE_SPRITES; }\n"}});
    const auto v = run(program, 8);
    EXPECT_EQ(v[0], std::int32_t(StyleRole::Off));
    EXPECT_EQ(v[1], std::int32_t(StyleRole::ClipAway));
    EXPECT_EQ(v[2], std::int32_t(StyleRole::ClipTo));
    EXPECT_EQ(v[3], std::int32_t(StyleRole::Style));
    EXPECT_EQ(v[4], std::int32_t(StyleRole::Lens));
    EXPECT_EQ(v[5], std::int32_t(StyleCombine::Union));
    EXPECT_EQ(v[6], std::int32_t(StyleCombine::Intersection));
    EXPECT_EQ(std::uint32_t(v[7]), StyleOptions().slots);
}

TEST_F(StyleBindingTest, UnusedSlotsDoNotCollideWithTheApplicationsSamplerOnUnitZero) {
    BakeOptions o;
    o.resolution = 32;
    o.method = BakeMethod::Cpu;
    const GpuSprite lens(gl(), bakeCpu(solids::box({0, 0, 0}, {1, 1, 1}).mesh, o));
    // The application's own 2D texture on unit 0, sampled by the same program.
    Texture texture = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(texture.id(), 1, GL_R32F, 1, 1);
    const float value = 0.25f;
    glTextureSubImage2D(texture.id(), 0, 0, 0, 1, 1, GL_RED, GL_FLOAT, &value);
    glBindTextureUnit(0, texture.id());
    const Program program = buildProgram(
        {{GL_COMPUTE_SHADER, "app.comp",
          "#version 450 core\n#include \"vds/styles.glsl\"\nlayout(local_size_x = 1) in;\nuniform sampler2D u_app;\n"
          "layout(std430, binding = 0) buffer B { int v[3]; };\n"
          "void main() { v[0] = vdsStyleAt(vec3(0.5)).style; v[1] = vdsStyleAt(vec3(2.0)).style;\n"
          "  v[2] = int(texture(u_app, vec2(0.5)).r * 100.0); }\n"}});
    while (glGetError() != GL_NO_ERROR) {
    }
    StyleOptions options;
    options.baseUnit = 4;
    const std::uint32_t next = setStyleUniforms(program.id(), {{&lens, StyleRole::Lens, 5, Rule::Parity}}, options);
    EXPECT_EQ(next, 5u);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    const auto v = run(program, 3);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "the dispatch was refused";
    EXPECT_EQ(v[0], 5) << "inside the lens";
    EXPECT_EQ(v[1], 0) << "outside: the base style";
    EXPECT_EQ(v[2], 25) << "the application's sampler";
    EXPECT_THROW(setStyleUniforms(program.id(), std::vector<StyleSolid>(9), options), InvalidArgument);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(4, 0);
}

} // namespace
} // namespace vds
