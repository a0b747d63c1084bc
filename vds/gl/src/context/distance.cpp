// vds::gl: a signed distance grid as a 3D texture (<vds/gl/distance.h>).
#include <vds/gl/distance.h>

#include <string>
#include <vector>

#include <vds/error.h>

namespace vds {

Texture uploadDistanceTexture(const Grid& grid, const float* cells) {
    checkGrid(grid);
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
    for (int a = 0; a < 3; ++a)
        if (grid.dims[a] > std::uint32_t(maxSize))
            throw OutOfMemory("a distance texture of " + std::to_string(grid.dims[a]) + " texels along " + "xyz"[a] +
                              " is above this GL's 3D texture size, " + std::to_string(maxSize));
    // Grid order is z fastest, GL's x fastest: texel (i, j, k) at i + w (j + h k).
    std::vector<float> texels(grid.cellCount());
    for (std::uint32_t i = 0; i < grid.dims.x; ++i)
        for (std::uint32_t j = 0; j < grid.dims.y; ++j)
            for (std::uint32_t k = 0; k < grid.dims.z; ++k)
                texels[i + std::size_t(grid.dims.x) * (j + std::size_t(grid.dims.y) * k)] = cells[grid.index(i, j, k)];
    Texture texture = Texture::create(GL_TEXTURE_3D);
    const GLuint id = texture.id();
    glTextureStorage3D(id, 1, GL_R32F, GLsizei(grid.dims.x), GLsizei(grid.dims.y), GLsizei(grid.dims.z));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(id, 0, 0, 0, 0, GLsizei(grid.dims.x), GLsizei(grid.dims.y), GLsizei(grid.dims.z), GL_RED,
                        GL_FLOAT, texels.data());
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(id, wrap, GL_CLAMP_TO_EDGE);
    if (glGetError() == GL_OUT_OF_MEMORY) throw OutOfMemory("no GL memory for a distance texture");
    return texture;
}

} // namespace vds
