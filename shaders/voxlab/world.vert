#version 330 core
// Object-order renderers (texture slicing) draw proxy geometry given in
// world coordinates; u_clip_from_world (Camera::clipFromWorld) places each
// point on the pixel whose ray passes through it, so slices and ray casting
// share one camera.
layout(location = 0) in vec3 a_position;

uniform mat4 u_clip_from_world;

out vec3 v_world;

void main() {
    v_world = a_position;
    gl_Position = u_clip_from_world * vec4(a_position, 1.0);
}
