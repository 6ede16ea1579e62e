// Stage: splatting, the footprint. (The walk, back to front, is the C++
// half of the stage: splat_order.cpp.)
//
// Every voxel the transfer function shows is a Gaussian blob of matter
// with standard deviation sigma (world units) around its centre. Seen along
// a ray, its matter adds up to the footprint
//     g(r) = exp(-r^2 / (2 sigma^2)) / (2 pi sigma^2)
// at distance r from its projected centre, times its volume V: L(r) = V g(r)
// world units of matter on that ray. The 2 pi sigma^2 makes the footprint
// integrate to 1 over the image plane, so that a splat, summed over all the
// pixels it covers, is exactly one voxel's worth of matter, whatever sigma
// is: a larger kernel blurs, it does not add or remove material.
//
// The transfer function's alpha is an opacity per unit length (u_min_spacing
// world units), so over L world units the splat's opacity is
//     a = 1 - (1 - alpha)^(L / u_min_spacing),
// the same opacity correction ray casting applies for a step.
//
// The framework (framework/stages/splat/splat.frag) finds r for each pixel of the
// splat, classifies the voxel's value with the transfer function, calls the
// two functions below, and blends the splat over what is behind it.
#ifndef VOXLAB_STAGE_SPLAT_GLSL
#define VOXLAB_STAGE_SPLAT_GLSL

#include "voxlab/volume.glsl"

// The footprint g(r) at distance r (world units) from the splat's centre,
// for a Gaussian of standard deviation sigma (world units): per unit area.
float splat_footprint(float r, float sigma) {
    // BEGIN SOLUTION
    const float pi = 3.14159265358979;
    return exp(-r * r / (2.0 * sigma * sigma)) / (2.0 * pi * sigma * sigma);
    // END SOLUTION
}

// The splat's opacity where its footprint is `footprint`: a voxel of volume
// `voxel_volume` (world units cubed) and opacity `alpha` per unit length.
float splat_opacity(float alpha, float footprint, float voxel_volume) {
    // BEGIN SOLUTION
    float length_units = voxel_volume * footprint / u_min_spacing;
    return 1.0 - pow(1.0 - clamp(alpha, 0.0, 1.0), length_units);
    // END SOLUTION
}

#endif
