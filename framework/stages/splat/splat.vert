#version 330 core
// Renderer "splat": one voxel's footprint as a square facing the camera,
// drawn once per visible voxel (instanced: a_point is the voxel's, the
// six vertices are the square's two triangles). The square reaches
// u_splat_cutoff standard deviations from the voxel's centre across the
// view, in the plane through the voxel perpendicular to the view direction,
// where the footprint is measured (splatting.h). The footprint itself and
// its opacity are the splat stage's (splat/splat.glsl).
layout(location = 0) in vec4 a_point;  // the voxel's world centre and its value

uniform mat4 u_clip_from_world;
uniform vec3 u_cam_right;
uniform vec3 u_cam_down;
uniform float u_splat_sigma;   // world units
uniform float u_splat_cutoff;  // in sigmas

out float v_value;
out vec2 v_offset;  // world units across the view from the voxel's centre
out vec3 v_centre;

const vec2 kCorners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, -1.0),
                                 vec2(1.0, 1.0), vec2(-1.0, 1.0));

void main() {
    float reach = u_splat_cutoff * u_splat_sigma;
    v_offset = reach * kCorners[gl_VertexID];
    vec3 world = a_point.xyz + v_offset.x * u_cam_right + v_offset.y * u_cam_down;
    gl_Position = u_clip_from_world * vec4(world, 1.0);
    v_value = a_point.w;
    v_centre = a_point.xyz;
}
