// Sample: render a mesh offscreen, clipped pixel-precisely by up to eight
// volumetric depth sprites in one pass (Trapp & Doellner 2008, Figure 1),
// through the GLSL include shaders/vds/vpt.glsl, and write a PNG.
//
//   vds_clip MESH --clip A.vds [--clip B.vds ...] -o out.png [--size N] [--view iso|x|y|z] [--rule parity|winding]
//   (vds_clip --help lists the defaults)
//
// Every fragment of MESH inside any sprite is discarded; back faces seen
// through the cut are drawn in red. The camera is orthographic, fitted to
// MESH's bounding box.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <vds/error.h>
#include <vds/gl_context.h>
#include <vds/gpu_mesh.h>
#include <vds/gpu_sprite.h>
#include <vds/eval/image.h>
#include <vds/mesh_io.h>
#include <vds/shader.h>
#include <vds/vds_file.h>

namespace vds::samples {
// This sample's shaders (shaders/samples/clip.*), embedded by vds_embed_shaders.
extern const vds::ShaderFile kSampleShaders[];
extern const std::size_t kSampleShadersCount;
} // namespace vds::samples

namespace {

struct Options {
    std::string mesh, output, view = "iso";
    std::vector<std::string> clips;
    std::uint32_t size = 800;
    std::string rule = vds::enumName(vds::Rule::Parity);
};

glm::mat4 camera(const vds::Box& box, const std::string& view) {
    const glm::vec3 centre = 0.5f * (box.lo + box.hi);
    const float radius = 0.5f * glm::length(box.hi - box.lo);
    glm::vec3 direction(0.8f, 0.55f, 1.0f), up(0, 1, 0);
    if (view == "x") direction = {1, 0, 0};
    else if (view == "y") { direction = {0, 1, 0}; up = {0, 0, -1}; }
    else if (view == "z") direction = {0, 0, 1};
    const glm::mat4 lookAt = glm::lookAt(centre + 3.0f * radius * glm::normalize(direction), centre, up);
    const glm::mat4 ortho = glm::ortho(-radius, radius, -radius, radius, 0.5f * radius, 6.0f * radius);
    return ortho * lookAt;
}

int run(const Options& o) {
    const vds::TriangleMesh mesh = vds::loadMesh(o.mesh);
    vds::requireUsable(vds::validateMesh(mesh), o.mesh);
    std::vector<vds::Sprite> sprites;
    for (const auto& path : o.clips) sprites.push_back(vds::readSprite(path));

    vds::GlContext gl;
    std::vector<vds::GpuSprite> gpuSprites;
    for (const auto& s : sprites) gpuSprites.emplace_back(s);
    vds::registerShaders(vds::samples::kSampleShaders, vds::samples::kSampleShadersCount);
    const vds::Program program = vds::buildProgram(
        {{GL_VERTEX_SHADER, "samples/clip.vert", ""}, {GL_FRAGMENT_SHADER, "samples/clip.frag", ""}});

    // Offscreen target.
    const GLsizei n = GLsizei(o.size);
    vds::Texture colour = vds::Texture::create(GL_TEXTURE_2D), depth = vds::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(colour.id(), 1, GL_RGBA8, n, n);
    glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, n, n);
    vds::Framebuffer fbo = vds::Framebuffer::create();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    if (glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw vds::GlError("offscreen framebuffer is incomplete");

    const vds::GpuMesh gpuMesh(mesh);

    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, n, n);
    const float white[4] = {1, 1, 1, 1};
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, white);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(program.id());
    const glm::mat4 viewProjection = camera(vds::meshBounds(mesh), o.view);
    glUniformMatrix4fv(glGetUniformLocation(program.id(), "u_viewProjection"), 1, GL_FALSE,
                       glm::value_ptr(viewProjection));
    glUniform3f(glGetUniformLocation(program.id(), "u_lightDirection"), 0.40f, 0.58f, 0.71f);
    glUniform3f(glGetUniformLocation(program.id(), "u_frontColour"), 0.85f, 0.82f, 0.74f);
    glUniform3f(glGetUniformLocation(program.id(), "u_cutColour"), 0.85f, 0.15f, 0.12f);
    glUniform1i(glGetUniformLocation(program.id(), "u_rule"), vds::parseRule(o.rule) == vds::Rule::Parity ? 0 : 1);
    glUniform1i(glGetUniformLocation(program.id(), "u_clipCount"), GLint(gpuSprites.size()));
    for (std::size_t i = 0; i < gpuSprites.size(); ++i)
        gpuSprites[i].setUniforms(program.id(), "u_ldi[" + std::to_string(i) + "]",
                                  "u_placement[" + std::to_string(i) + "]", GLuint(i));
    // Unused sampler slots still need a 3D texture bound; point them at the first sprite's unit.
    for (std::size_t i = gpuSprites.size(); i < 8; ++i)
        glUniform1i(glGetUniformLocation(program.id(), ("u_ldi[" + std::to_string(i) + "]").c_str()), 0);
    gpuMesh.draw();
    vds::checkGl("rendering");

    vds::eval::Image image(o.size, o.size);
    std::vector<std::uint8_t> pixels(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(colour.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    const std::size_t row = std::size_t(o.size) * 4;
    for (std::uint32_t y = 0; y < o.size; ++y) // GL rows run bottom to top, PNG rows top to bottom
        std::memcpy(image.at(0, y), &pixels[(o.size - 1 - y) * row], row);
    vds::eval::writePng(image, o.output);
    std::printf("wrote %s: %ux%u, %s clipped by %zu sprite(s), GL %s\n", o.output.c_str(), o.size, o.size,
                o.mesh.c_str(), sprites.size(), gl.info().renderer.c_str());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app("Renders MESH with every fragment inside any of the sprites discarded, pixel-precisely, in one\n"
                 "pass; back faces seen through the cut are red.",
                 "vds_clip");
    app.get_formatter()->label("Usage", "usage");
    app.option_defaults()->always_capture_default();
    app.add_option("MESH", o.mesh, "mesh to render (OBJ, PLY, STL, OFF)")->required()->type_name("");
    app.add_option("--clip", o.clips, "a sprite that cuts the mesh; 1 to 8 of them")
        ->required()
        ->expected(1, 8)
        ->allow_extra_args(false)
        ->type_name("SPRITE.vds");
    app.add_option("-o,--output", o.output, "the picture")->required()->type_name("OUT.png");
    app.add_option("--size", o.size, "image width and height in pixels")->check(CLI::Range(16u, 8192u));
    app.add_option("--view", o.view, "look along -x, -y, -z or diagonally")->check(CLI::IsMember({"iso", "x", "y", "z"}));
    app.add_option("--rule", o.rule, "inside rule for the sprites")->check(CLI::IsMember(vds::enumNames<vds::Rule>()));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help
        std::fprintf(stderr, "vds_clip: %s (try 'vds_clip --help')\n", e.what());
        return 2;
    }
    try {
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vds_clip: error: %s\n", e.what());
        return 1;
    }
}
