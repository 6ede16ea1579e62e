// voxlab: parameters that several renderers declare alike. Each renderer
// still lists them in its own parameters(), so `voxlab list`, scene files
// and the viewer see them as that renderer's.
#include "voxlab/renderers.h"

namespace voxlab {

std::vector<ParameterSpec> shadingParameters(bool shadingByDefault) {
    using T = ParameterType;
    return {
        {"shading", T::Bool, 0, 1, shadingByDefault ? 1.0 : 0.0, "light samples by their gradient (Phong)"},
        {"blinn", T::Bool, 0, 1, 0, "Blinn-Phong's half vector instead of Phong's reflection vector"},
        {"ka", T::Float, 0, 1, 0.2, "ambient coefficient"},
        {"kd", T::Float, 0, 1, 0.7, "diffuse coefficient"},
        {"ks", T::Float, 0, 1, 0.3, "specular coefficient (white highlight)"},
        {"shininess", T::Float, 1, 256, 24, "specular exponent: larger is a smaller, sharper highlight"},
        {"light_azimuth", T::Float, -180, 180, 0,
         "light direction: degrees to the right of the view direction (0 with elevation 0: headlight)"},
        {"light_elevation", T::Float, -90, 90, 0, "light direction: degrees above the view direction"},
        {"min_gradient", T::Float, 0, 1, 0.002,
         "gradient magnitude below which a sample is left unlit, as a fraction of the value range per unit length"},
        {"sobel", T::Bool, 0, 1, 0, "26-neighbour (Sobel-like) gradient instead of central differences"},
        {"precomputed_gradients", T::Bool, 0, 1, 0,
         "read gradients from a volume computed on the CPU (12 bytes per voxel) instead of estimating them"},
    };
}

namespace {
constexpr const char* kEarlyTermination = "early_termination";
constexpr const char* kBackToFront = "back_to_front";
}  // namespace

std::vector<ParameterSpec> compositingParameters() {
    using T = ParameterType;
    return {
        {kEarlyTermination, T::Float, 0.5, 1, 0.99, "stop a ray once its opacity reaches this (1: never stop early)"},
        {kBackToFront, T::Bool, 0, 1, 0, "accumulate from the back (no early termination; same image)"},
        {"jitter", T::Bool, 0, 1, 0, "start each ray at a random fraction of a step (turns rings into noise)"},
    };
}

ProfileSettings compositingProfileSettings(const ParameterValues& values) {
    ProfileSettings settings;
    if (values.at(kBackToFront) == 0.0) settings.earlyTermination = values.at(kEarlyTermination);
    return settings;
}

}  // namespace voxlab
