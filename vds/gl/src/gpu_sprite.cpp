#include <vds/gpu_sprite.h>

#include <algorithm>
#include <vector>

#include <GL/glext.h>

#include <vds/error.h>
#include <vds/shader.h>

namespace vds {

GpuSprite::GpuSprite(const Sprite& sprite) {
    const std::uint32_t w = sprite.width(), h = sprite.height(), d = std::max<std::uint32_t>(1, sprite.depthComplexity);
    GLint max3d = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    if (w > std::uint32_t(max3d) || h > std::uint32_t(max3d) || d > std::uint32_t(max3d))
        throw InvalidArgument("sprite " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d) +
                              " exceeds this GL's 3D texture limit " + std::to_string(max3d) +
                              "; bake at a lower resolution");
    std::vector<float> dense;
    try {
        dense.assign(std::size_t(w) * h * d, 1.0f);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory("not enough memory for a " + std::to_string(w) + "x" + std::to_string(h) + "x" +
                          std::to_string(d) + " texture");
    }
    const std::size_t layer = std::size_t(w) * h;
    for (std::size_t c = 0; c < layer; ++c)
        for (std::uint32_t k = sprite.offsets[c]; k < sprite.offsets[c + 1]; ++k)
            dense[(k - sprite.offsets[c]) * layer + c] = sprite.crossings[k];

    texture_ = Texture::create(GL_TEXTURE_3D);
    glTextureStorage3D(texture_.id(), 1, GL_R32F, GLsizei(w), GLsizei(h), GLsizei(d));
    checkGl("allocating the sprite texture");
    glTextureSubImage3D(texture_.id(), 0, 0, 0, 0, GLsizei(w), GLsizei(h), GLsizei(d), GL_RED, GL_FLOAT, dense.data());
    glTextureParameteri(texture_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(texture_.id(), wrap, GL_CLAMP_TO_BORDER);
    const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glTextureParameterfv(texture_.id(), GL_TEXTURE_BORDER_COLOR, border);
    checkGl("uploading the sprite texture");
    size_ = {w, h, d};
    setPlacement(sprite.grid);
}

void GpuSprite::setPlacement(const SpriteGrid& grid) {
    matrix_ = grid.matrix;
    position_ = grid.position;
}

void GpuSprite::bind(GLuint unit) const { glBindTextureUnit(unit, texture_.id()); }

void GpuSprite::setUniforms(GLuint program, const std::string& sampler, const std::string& placement,
                            GLuint unit) const {
    bind(unit);
    glUniform1i(glGetUniformLocation(program, sampler.c_str()), GLint(unit));
    glUniformMatrix3fv(glGetUniformLocation(program, (placement + ".matrix").c_str()), 1, GL_FALSE, &matrix_[0][0]);
    glUniform3fv(glGetUniformLocation(program, (placement + ".position").c_str()), 1, &position_[0]);
}

GpuClassifier::GpuClassifier(const GlContext& gl) : gl_(&gl) {
    gl.program("vds.classify", [] { return buildProgram({{GL_COMPUTE_SHADER, "vds/classify.comp", ""}}); });
}

void GpuClassifier::classify(const GpuSprite& sprite, const glm::vec3* points, std::size_t count,
                             std::uint8_t* labels, Rule rule, std::size_t batch) const {
    const Program& program =
        gl_->program("vds.classify", [] { return buildProgram({{GL_COMPUTE_SHADER, "vds/classify.comp", ""}}); });
    batch = std::max<std::size_t>(256, std::min<std::size_t>(batch, std::size_t(65535) * 256));
    const std::size_t n = std::min(batch, count);
    Buffer pointBuffer = Buffer::create(), labelBuffer = Buffer::create();
    glNamedBufferStorage(pointBuffer.id(), GLsizeiptr(std::max<std::size_t>(n, 1) * 12), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(labelBuffer.id(), GLsizeiptr(std::max<std::size_t>(n, 1) * 4), nullptr, 0);
    checkGl("allocating classification buffers");
    glUseProgram(program.id());
    sprite.setUniforms(program.id(), "u_ldi", "u_placement", 0);
    glUniform1i(glGetUniformLocation(program.id(), "u_rule"), rule == Rule::Winding ? 1 : 0);
    const GLint countLoc = glGetUniformLocation(program.id(), "u_count");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pointBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, labelBuffer.id());
    std::vector<std::uint32_t> out(n);
    for (std::size_t begin = 0; begin < count; begin += n) {
        const std::size_t m = std::min(n, count - begin);
        glNamedBufferSubData(pointBuffer.id(), 0, GLsizeiptr(m * 12), points + begin);
        glUniform1ui(countLoc, GLuint(m));
        glDispatchCompute(GLuint((m + 255) / 256), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        glGetNamedBufferSubData(labelBuffer.id(), 0, GLsizeiptr(m * 4), out.data());
        for (std::size_t k = 0; k < m; ++k) labels[begin + k] = std::uint8_t(out[k]);
    }
    glUseProgram(0);
    glBindTextureUnit(0, 0);
    checkGl("classifying points on the GPU");
}

} // namespace vds
