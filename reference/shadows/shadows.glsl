// Stage: shadows from a light volume.
//
// Phong shading lights a sample as if nothing stood between it and the
// light. A volume casts shadows on itself: light that reaches a sample has
// passed through everything between the sample and the light, and each
// sample on the way lets only 1 - a of it through. The light that arrives,
// as a fraction, is the transmittance along the shadow ray, the ray from
// the sample towards the light:
//     T(p) = prod_k (1 - a_k),   a_k = opacity_correction(alpha(q_k), step / u_min_spacing)
// over samples q_k = p + k step L (k = 1, 2, ...; L the unit vector towards
// the light) while q_k is inside the volume's box. The first sample is one
// step away: the sample p does not shadow itself. alpha is the transfer
// function's opacity per unit length of the value at q_k, clamped to
// [0, 1]; `step` is in world units, so the opacity is corrected for
// step / u_min_spacing unit lengths. Once T is below 1/1000, you may stop:
// nothing visible changes.
//
// A shadow ray per sample of every camera ray would cost hundreds of
// samples per sample. Instead the framework evaluates your function once
// per voxel of a light volume (`shadow_resolution`, 64 by default, voxels
// on each axis at most), a 3D texture
// of T (Behrens and Ratering 1998 build the same thing by slicing; Levoy
// 1988's two-pass idea): see framework/stages/shadows/light_volume.frag. It
// recomputes it when the transfer function, the light direction (which
// turns with the camera) or the volume changes. The composite renderer,
// with `shadows` on, then multiplies each lit sample's colour by T read
// from the light volume one light-volume voxel towards the light from p (so
// that a sample just under a surface does not read the surface's shadow). The light direction is lighting.glsl's
// light_direction(), set by `light_azimuth` and `light_elevation`.
#ifndef VOXLAB_STAGE_SHADOWS_GLSL
#define VOXLAB_STAGE_SHADOWS_GLSL

#include "voxlab/volume.glsl"
#include "voxlab/classify.glsl"

// The transmittance from p towards the light (unit vector `to_light`),
// sampled every `step` world units, in [0, 1].
float light_transmittance(vec3 p, vec3 to_light, float step) {
    // BEGIN SOLUTION
    float transmittance = 1.0;
    for (int k = 1; transmittance > 1e-3; ++k) {
        vec3 q = p + float(k) * step * to_light;
        if (!inside_volume(q)) break;
        float alpha = clamp(transfer_function(sample_volume(q)).a, 0.0, 1.0);
        transmittance *= 1.0 - opacity_correction(alpha, step / u_min_spacing);
    }
    return transmittance;
    // END SOLUTION
}

#endif
