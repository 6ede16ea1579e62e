#version 330 core
// Object-order renderers (texture slicing) draw proxy geometry given in
// world coordinates; u_clip_from_world (Camera::clipFromWorld) places each
// point on the pixel whose ray passes through it, so slices and ray casting
// share one camera.
layout(location = 0) in vec3 a_position;
// The triangle's own normal (DrawContext::drawFacets; zero when not given).
layout(location = 1) in vec3 a_face_normal;

uniform mat4 u_clip_from_world;

out vec3 v_world;
flat out vec3 v_face_normal;

void main() {
    v_world = a_position;
    v_face_normal = a_face_normal;
    gl_Position = u_clip_from_world * vec4(a_position, 1.0);
}
