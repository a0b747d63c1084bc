// Local slicing, first pass (Eisemann & Decoret 2006, section 2.3): the near
// and far depth of every column, into two R32F targets blended with GL_MIN
// and GL_MAX.
in float v_depth;
layout(location = 0) out float o_near;
layout(location = 1) out float o_far;

void main() {
    o_near = v_depth;
    o_far = v_depth;
}
