// Stage: gradient-magnitude opacity modulation (boundary emphasis).
//
// A transfer function of the value alone gives a whole organ or a whole
// block of wood one opacity, so the inside of a homogeneous region hides
// what lies behind it. Where two materials meet the value changes fast:
// the gradient's magnitude |grad f| is large on boundaries and near zero
// inside homogeneous regions. Multiplying each sample's opacity by a
// function of |grad f| lets the regions fade and keeps their boundaries
// (Levoy, "Display of surfaces from volume data", 1988, section 3:
// opacity scaled by the gradient magnitude; the TU/e reports' "gradient
// opacity weighting").
//
// The function here is a ramp with two bounds, both in data units per unit
// length (the smallest spacing), the units of gradient_at():
//
//     w(g) = 0                          for g <= low
//          = (g - low) / (high - low)   for low < g < high
//          = 1                          for g >= high
//
// and, when high <= low, a step: w = 0 below high, 1 from high on.
// The composite renderer multiplies the sample's opacity (per unit length,
// before opacity correction) by w(|grad f|) when its parameter
// `gradient_opacity` is on, with low = `gradient_low` and high =
// `gradient_high`.
#ifndef VOXLAB_STAGE_GRADIENT_OPACITY_GLSL
#define VOXLAB_STAGE_GRADIENT_OPACITY_GLSL

// The opacity weight of a sample whose gradient magnitude is
// gradient_magnitude (data units per unit length), in [0, 1].
float gradient_opacity_weight(float gradient_magnitude, float low, float high) {
    // BEGIN SOLUTION
    if (high <= low) return gradient_magnitude < high ? 0.0 : 1.0;
    return clamp((gradient_magnitude - low) / (high - low), 0.0, 1.0);
    // END SOLUTION
}

#endif
