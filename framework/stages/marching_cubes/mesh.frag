#version 330 core
// Renderer "mesh": one fragment of the isosurface's triangle mesh, made on
// the CPU by marching cubes (framework/stages/marching_cubes/mesh.cpp, with
// the marching_cubes stage's cubeCase and edgeCrossing) and drawn with a
// depth test. Shaded as iso shades its hits (the gradient at the point, the
// shading stage), or by the triangle's own normal with `flat` (the facets
// marching cubes made), or as its depth with `depth`, on the same grey scale
// as iso's depth image (depth_grey), so the two can be compared.
#include "voxlab/ray.glsl"
#include "voxlab/output.glsl"
#include "voxlab/lighting.glsl"

uniform float u_color_r;
uniform float u_color_g;
uniform float u_color_b;
uniform int u_depth;
uniform int u_flat;
uniform int u_mesh_lines;  // drawing the wireframe's lines

in vec3 v_world;
flat in vec3 v_face_normal;  // the triangle's (DrawContext::drawFacets)
out vec4 frag_color;

// The fragment's depth for the depth test: its distance along the view
// from the box's bounding sphere's near side, over the sphere's diameter.
float view_depth(vec3 p) {
    vec3 centre = 0.5 * u_volume_extent;
    float radius = 0.5 * length(u_volume_extent);
    float nearest = dot(centre - u_cam_position, u_cam_forward) - radius;
    return clamp((dot(p - u_cam_position, u_cam_forward) - nearest) / (2.0 * radius), 0.0, 1.0);
}

void main() {
    if (!inside_region(v_world)) discard;
    gl_FragDepth = view_depth(v_world);
    if (u_mesh_lines != 0) {
        gl_FragDepth = max(view_depth(v_world) - 1e-4, 0.0);  // over its own triangles
        frag_color = vec4(0.1, 0.1, 0.1, 1.0);
        return;
    }
    Ray ray;
    ray.origin = u_orthographic != 0 ? v_world - dot(v_world - u_cam_position, u_cam_forward) * u_cam_forward
                                     : u_cam_position;
    ray.direction = u_orthographic != 0 ? u_cam_forward : normalize(v_world - u_cam_position);
    ray.t_entry = 0.0;
    ray.t_exit = -1.0;
    if (u_depth != 0) {
        frag_color = finish(vec4(vec3(depth_grey(ray, dot(v_world - ray.origin, ray.direction))), 1.0));
        return;
    }
    vec3 colour = vec3(u_color_r, u_color_g, u_color_b);
    if (u_flat != 0 && u_shading != 0) {
        // The triangle's own normal: the same on every GL, where one made
        // from dFdx/dFdy is not at a small triangle's pixels.
        vec3 n = dot(v_face_normal, v_face_normal) > 0.0 ? v_face_normal
                                                          : normalize(cross(dFdx(v_world), dFdy(v_world)));
        if (dot(n, -ray.direction) < 0.0) n = -n;
        colour = phong(colour, n, light_direction(), -ray.direction);
    } else {
        colour = shade_sample(colour, v_world, ray);
    }
    frag_color = finish(vec4(colour, 1.0));
}
