// vds's GL headers after an application's GL loader (libepoxy here): the
// translation unit includes <epoxy/gl.h> first, as such applications must,
// then every public vds GL header, and uses both: epoxy's GL calls and
// vds's objects in one context.
#include <epoxy/gl.h>

#include <cstdio>
#include <string>
#include <vector>

#include <vds/bake.h>
#include <vds/gl/bake.h>
#include <vds/gl/classifier.h>
#include <vds/gl/context.h>
#include <vds/gl/mesh.h>
#include <vds/gl/objects.h>
#include <vds/gl/occupancy.h>
#include <vds/gl/shader.h>
#include <vds/gl/sprite.h>
#include <vds/gl/styles.h>
#include <vds/voxel/gpu_grid.h>
#include <vds/voxel/refraction.h>
#include <vds/voxel/representation.h>
#include <vds/voxel/slicemap.h>
#include <vds/voxel/solid.h>
#include <vds/voxel/transmittance.h>

int main() {
    std::string why;
    if (!vds::glAvailable(&why)) {
        std::printf("no GL (%s): nothing to check\n", why.c_str());
        return 0;
    }
    const vds::GlContext gl;
    if (epoxy_gl_version() < 43) {
        std::printf("epoxy sees GL %d\n", epoxy_gl_version());
        return 1;
    }
    // A box, baked on the CPU and uploaded; its inside read by the application's
    // own shader, built with epoxy's entry points and set up by vds.
    vds::TriangleMesh box;
    box.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    box.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                     {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {3, 0, 4}, {3, 4, 7}};
    vds::BakeOptions options;
    options.resolution = 16;
    options.method = vds::BakeMethod::Cpu;
    const vds::GpuSprite sprite(gl, vds::bakeCpu(box, options));
    const vds::Program program = vds::buildProgram(
        {{GL_COMPUTE_SHADER, "app.comp",
          "#include \"vds/vpt.glsl\"\nlayout(local_size_x = 1) in;\nuniform sampler3D u_ldi;\nuniform VdsPlacement u_p;\n"
          "layout(std430, binding = 0) buffer B { uint v[2]; };\n"
          "void main() { v[0] = vdsContains(u_ldi, u_p, vec3(0.5), VDS_RULE_PARITY) ? 1u : 0u;\n"
          "  v[1] = vdsContains(u_ldi, u_p, vec3(1.5), VDS_RULE_PARITY) ? 1u : 0u; }\n"}});
    sprite.setUniforms(program.id(), "u_ldi", "u_p", 2);
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    const GLuint init[2] = {7, 7};
    glNamedBufferData(buffer, sizeof init, init, GL_DYNAMIC_READ);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint labels[2] = {0, 0};
    glGetNamedBufferSubData(buffer, 0, sizeof labels, labels);
    glUseProgram(0);
    glDeleteBuffers(1, &buffer);
    std::printf("epoxy GL %d; inside %u, outside %u\n", epoxy_gl_version(), labels[0], labels[1]);
    return labels[0] == 1 && labels[1] == 0 && glGetError() == GL_NO_ERROR ? 0 : 1;
}
