// Links vds::gl from the installed package and embeds a shader of its own
// with the installed CMake function vds_embed_shaders: the table registers,
// and the shader assembles with its include of the library's vds/vpt.glsl
// resolved (no GL context needed). Exit 0 when both hold.
#include <cstdio>
#include <string>

#include <vds/gl/shader.h>

namespace consumer {
extern const vds::ShaderFile kConsumerShaders[];
extern const std::size_t kConsumerShadersCount;
} // namespace consumer

int main() {
    vds::registerShaders(consumer::kConsumerShaders, consumer::kConsumerShadersCount);
    const std::string source = vds::embeddedShader("consumer/tint.frag");
    const std::string assembled =
        vds::assembleShader({GL_FRAGMENT_SHADER, "consumer/tint.frag", ""}, "#version 430 core", "");
    const bool own = source.find("consumer_tint") != std::string::npos;
    const bool included = assembled.find("bool vdsContains(") != std::string::npos &&
                          assembled.find("consumer_tint") != std::string::npos;
    std::printf("embedded %zu file(s); own text %s; vds/vpt.glsl %s\n", consumer::kConsumerShadersCount,
                own ? "found" : "MISSING", included ? "included" : "NOT included");
    return consumer::kConsumerShadersCount == 1 && own && included ? 0 : 1;
}
