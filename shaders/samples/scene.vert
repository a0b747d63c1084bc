// Samples: the rendered model. World coordinates are the model's mesh
// coordinates. Gouraud shading is lit here, per vertex.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_viewProjection;
uniform vec3 u_lightDirection;

// The exact reference matches fragments of separate programs by depth.
invariant gl_Position;

out vec3 v_world;
out vec3 v_normal;
out float v_gouraud;

void main() {
    v_world = a_position;
    v_normal = a_normal;
    v_gouraud = 0.2 + 0.8 * abs(dot(normalize(a_normal), u_lightDirection));
    gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
