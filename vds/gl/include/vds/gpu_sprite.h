// vds: sprites on the GPU, for the GLSL include shaders/vds/vpt.glsl.
//
// `GpuSprite` turns a sprite into the paper's texture: a width x height x d_S
// R32F 3D texture, nearest filtering, border value 1, clamp to border (Trapp &
// Döllner 2008, section 4.1 step 2), padded with 1.0 behind each column's
// crossings. A shader needs the texture and the placement (P_S, M_S):
//   uniform sampler3D u_ldi; uniform VdsPlacement u_placement;
// `GpuClassifier` runs the same test over many points in a compute shader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <vds/gl_context.h>
#include <vds/gl_objects.h>
#include <vds/sprite.h>

namespace vds {

class GpuSprite {
public:
    GpuSprite() = default;
    /// Uploads `sprite` to the current context. Throws `InvalidArgument` if it
    /// exceeds GL_MAX_3D_TEXTURE_SIZE (bake at a lower resolution) and
    /// `OutOfMemory` if GL cannot hold it.
    explicit GpuSprite(const Sprite& sprite);

    const Texture& texture() const { return texture_; }
    glm::uvec3 size() const { return size_; }         ///< width, height, layers
    const glm::mat3& matrix() const { return matrix_; } ///< M_S
    const glm::vec3& position() const { return position_; } ///< P_S
    /// Moves the sprite on the GPU without re-uploading (see Sprite::transform).
    void setPlacement(const SpriteGrid& grid);

    /// Binds the texture to texture unit `unit`.
    void bind(GLuint unit) const;
    /// Binds to `unit` and sets, in `program` (which must be in use), the
    /// sampler uniform `sampler` and the VdsPlacement uniform `placement`
    /// (e.g. "u_ldi[2]" and "u_placement[2]"). Unknown names are ignored, as GL does.
    void setUniforms(GLuint program, const std::string& sampler, const std::string& placement, GLuint unit) const;

private:
    Texture texture_;
    glm::uvec3 size_{0};
    glm::mat3 matrix_{1.0f};
    glm::vec3 position_{0.0f};
};

/// Classifies points against a GpuSprite with a compute shader. Answers are
/// identical to `classify()` on the CPU for the same sprite and points.
class GpuClassifier {
public:
    /// Builds the compute program on `gl` (current). Throws `GlError`.
    explicit GpuClassifier(const GlContext& gl);
    /// `points` and `labels` hold `count` elements (caller-owned); labels get
    /// 1 inside, 0 outside. Points are sent in batches of `batch` points.
    void classify(const GpuSprite& sprite, const glm::vec3* points, std::size_t count, std::uint8_t* labels,
                  Rule rule = Rule::Parity, std::size_t batch = std::size_t(1) << 22) const;

private:
    const GlContext* gl_;
};

} // namespace vds
