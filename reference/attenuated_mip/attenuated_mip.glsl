// Stage: attenuated maximum intensity projection.
//
// A MIP shows the brightest sample along a ray wherever it lies, so a
// bright structure at the back shows through everything in front of it:
// MIP gives no depth. Attenuated MIP (offered by napari, for example) dims
// each sample by how much bright material the ray has already crossed, so
// what lies in front wins over what lies behind:
//
//     n_k = (f_k - lo) / (hi - lo)                  the sample normalised to
//                                                   the volume's range [lo, hi]
//     D_m = sum over k < m of n_k * u_step_units    the "optical depth" in
//                                                   front of sample m
//     I   = max over m of  lo + (f_m - lo) * exp(-u_attenuation * D_m)
//
// lo, hi = u_value_range. D_m counts the samples *before* m, in units of
// the smallest spacing (u_step_units), so the image does not change with
// the step. With u_attenuation = 0 this is the MIP.
//
// Depth cue (napari-style): each sample is also dimmed by how deep it lies,
// its distance s_m from where the ray enters the region it samples
// (t_entry), also in units of the smallest spacing:
//
//     s_m = (m + 1/2) * u_step_units                sample m sits at
//                                                   t_entry + (m + 1/2) u_step
//     I   = max over m of  lo + (f_m - lo) * exp(-u_attenuation * D_m)
//                                           * exp(-u_depth_cue * s_m)
//
// u_depth_cue is per unit length (smallest spacing): a sample 1/u_depth_cue
// spacings deep keeps 1/e of its height above lo. With u_depth_cue = 0
// there is no depth cue; both dimmings apply together.
#ifndef VOXLAB_STAGE_ATTENUATED_MIP_GLSL
#define VOXLAB_STAGE_ATTENUATED_MIP_GLSL

#include "voxlab/ray.glsl"

uniform float u_attenuation;  // per unit length of normalised intensity
uniform float u_depth_cue;    // per unit length (smallest spacing) of depth

// Returns the largest attenuated sample value along the ray (data units).
float attenuated_mip_ray(Ray ray) {
    // BEGIN SOLUTION
    float lo = u_value_range.x;
    float range = max(u_value_range.y - u_value_range.x, 1e-30);
    float depth = 0.0;
    float maximum = -3.4e38;
    int n = sample_count(ray);
    for (int m = 0; m < n; ++m) {
        float f = sample_volume(sample_position(ray, m));
        float dist = (float(m) + 0.5) * u_step_units;
        maximum = max(maximum, lo + (f - lo) * exp(-u_attenuation * depth) * exp(-u_depth_cue * dist));
        depth += (f - lo) / range * u_step_units;
    }
    return maximum;
    // END SOLUTION
}

#endif
