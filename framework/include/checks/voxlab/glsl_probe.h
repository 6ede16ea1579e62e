// voxlab (internal): running GLSL stage functions on many inputs at once,
// for the function checks (voxlab/function_checks.h).
//
// A probe is a fragment shader in a stage's folder (framework/stages/STAGE/
// STAGE_probe.frag, named "stages/STAGE/...") that includes the stage
// and calls its function once per pixel. Each case is one pixel: its inputs
// are texels of up to kProbeInputs RGBA32F textures (u_probe_input[k],
// read with PROBE_INPUT(k) from probes/probe.glsl), and the probe writes
// two RGBA32F results, read back as floats, unrounded. A third target
// records whether the pixel reached a stub's not_implemented().
//
// Functions that read uniforms the stage declares (u_ka, u_tf2d_shape[i],
// ...) can be given different values per case: `perCase` is then called
// before each case is drawn alone, into its own pixel.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "voxlab/gl_object.h"
#include "voxlab/shader.h"

namespace voxlab::probe {

constexpr int kProbeInputs = 6;

struct ProbeResults {
    std::vector<glm::vec4> first, second;  // per case
    bool notImplemented = false;           // some case called not_implemented()
};

// A float volume for the probes that sample (the uniforms of
// shaders/voxlab/volume.glsl): `values` x fastest, world box [0, extent].
struct ProbeVolume {
    glm::ivec3 dims{0};
    glm::vec3 extent{0.0f};
    std::vector<float> values;
    float valueScale = 1.0f, valueOffset = 0.0f;
    bool linearFilter = false;  // GL_LINEAR (the "hardware" interpolation) instead of GL_NEAREST
};

class GlslProbe {
public:
    // Compiles `fragmentName`, a stage's probe ("stages/STAGE/FILE", which
    // only the framework's stage folders answer; anything else is an Error),
    // against the implementation's stages, with voxlab/fullscreen.vert.
    // Throws ShaderError.
    GlslProbe(const std::string& implementationRoot, const std::string& fragmentName,
              const ShaderConstants& constants = {});
    ~GlslProbe();
    GlslProbe(const GlslProbe&) = delete;
    GlslProbe& operator=(const GlslProbe&) = delete;

    const ShaderProgram& program() const { return program_; }

    // Uploads the volume (texture unit 0, u_volume) and sets its uniforms,
    // u_min_spacing and u_value_range included.
    void setVolume(const ProbeVolume& volume);

    // Uploads a 1D transfer-function table (the uniforms of
    // shaders/voxlab/classify.glsl: u_tf on its own texture unit, u_tf_range,
    // u_tf_size): `entries` evenly over [range.x, range.y], at most 4096.
    void setTransferFunction(const std::vector<glm::vec4>& entries, glm::vec2 range);

    // Runs `cases` cases; inputs[k][i] is input k of case i.
    ProbeResults run(int cases, const std::vector<std::vector<glm::vec4>>& inputs,
                     const std::function<void(const ShaderProgram&, int)>& perCase = nullptr);

private:
    ShaderProgram program_;
    GlTexture volumeTexture_, tfTexture_;
};

}  // namespace voxlab::probe
