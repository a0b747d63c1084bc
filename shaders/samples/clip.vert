// Sample: pixel-precise clipping against several sprites in one pass.
layout(location = 0) in vec3 a_position;
uniform mat4 u_viewProjection;
out vec3 v_world;

void main() {
    v_world = a_position;
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
