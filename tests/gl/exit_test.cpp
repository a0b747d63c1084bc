// A program that keeps a GL context, a cached program and GL objects in
// statics until the process exits, as users do. It must exit cleanly (also
// under ASan, and on drivers that tear themselves down at exit): the library
// stops calling GL and EGL once exit has begun (<vds/gl/context.h>).
#include <cstdio>
#include <memory>

#include <vds/error.h>
#include <vds/gl/context.h>
#include <vds/gl/objects.h>
#include <vds/gl/shader.h>

namespace {
std::unique_ptr<vds::GlContext> gContext; // destroyed after main returns
vds::Buffer gBuffer;                      // likewise
} // namespace

int main() {
    std::string why;
    if (!vds::glAvailable(&why)) {
        std::printf("no GL (%s): nothing to check\n", why.c_str());
        return 0;
    }
    gContext = std::make_unique<vds::GlContext>();
    gContext->program("exit.compute", [] {
        return vds::buildProgram({{GL_COMPUTE_SHADER, "exit.comp", "layout(local_size_x = 1) in; void main() {}\n"}});
    });
    gBuffer = vds::Buffer::create();
    static vds::Program program =
        vds::buildProgram({{GL_COMPUTE_SHADER, "exit2.comp", "layout(local_size_x = 1) in; void main() {}\n"}});
    std::printf("context %s, program %u, buffer %u kept until exit\n", gContext->info().renderer.c_str(),
                program.id(), gBuffer.id());
    return 0;
}
