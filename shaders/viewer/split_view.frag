#version 330 core
// voxlab viewer: puts the rendered images on the screen.
//   u_mode 0  one image (the left), scaled to the window (a reduced-size
//             image while the mouse drags is filtered up);
//   u_mode 1  split view: the left image left of the divider, the right
//             image right of it;
//   u_mode 2  difference: a heat map of the largest per-channel |left - right|,
//             amplified four times (black: equal; purple, orange, yellow: more).
// With u_count_scale > 0 the images hold sample counts in red (the samples
// view): each is shown as heat(count * u_count_scale) first. With
// u_image_aspect > 0 (a student release comparing with an expected image)
// the images keep that width / height, centred, on dark grey. While a large
// image is rendered a band of rows at a time (the viewer's viewer_tiles.cpp),
// the rows below u_new_from (a texture coordinate) are not yet rendered:
// there the previews, the images shown before, show instead.
uniform sampler2D u_left;
uniform sampler2D u_right;
uniform sampler2D u_left_preview;
uniform sampler2D u_right_preview;
uniform float u_new_from;
uniform vec2 u_viewport_size;  // framebuffer pixels
uniform float u_divider;       // framebuffer x of the divider
uniform int u_mode;
uniform float u_count_scale;
uniform float u_image_aspect;

out vec4 frag_color;

vec3 heat(float t) {
    t = clamp(t, 0.0, 1.0);
    vec3 c0 = vec3(0.0), c1 = vec3(0.35, 0.05, 0.55), c2 = vec3(0.95, 0.35, 0.15), c3 = vec3(1.0, 0.95, 0.55);
    if (t < 1.0 / 3.0) return mix(c0, c1, 3.0 * t);
    if (t < 2.0 / 3.0) return mix(c1, c2, 3.0 * t - 1.0);
    return mix(c2, c3, 3.0 * t - 2.0);
}

vec3 image(sampler2D side, sampler2D preview, vec2 uv) {
    vec3 c = uv.y >= u_new_from ? texture(side, uv).rgb : texture(preview, uv).rgb;
    return u_count_scale > 0.0 ? heat(c.r * u_count_scale) : clamp(c, 0.0, 1.0);
}

void main() {
    vec2 uv = gl_FragCoord.xy / u_viewport_size;
    if (u_image_aspect > 0.0) {
        float window = u_viewport_size.x / u_viewport_size.y;
        vec2 scale = window > u_image_aspect ? vec2(window / u_image_aspect, 1.0) : vec2(1.0, u_image_aspect / window);
        uv = (uv - 0.5) * scale + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
            frag_color = vec4(0.12, 0.12, 0.12, 1.0);
            return;
        }
    }
    vec3 left = image(u_left, u_left_preview, uv);
    if (u_mode == 0) {
        frag_color = vec4(left, 1.0);
        return;
    }
    vec3 right = image(u_right, u_right_preview, uv);
    if (u_mode == 1) {
        frag_color = vec4(gl_FragCoord.x < u_divider ? left : right, 1.0);
        return;
    }
    vec3 d = abs(left - right);
    frag_color = vec4(heat(4.0 * max(d.r, max(d.g, d.b))), 1.0);
}
