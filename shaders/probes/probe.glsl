// voxlab GLSL library for the function checks' probes (see
// framework/include/checks/voxlab/glsl_probe.h): one case per pixel. A case's inputs
// are texels of the RGBA32F textures u_probe_input[k]; its results go to
// two RGBA32F targets, and a third records whether a stub was reached.
#ifndef VOXLAB_PROBE_GLSL
#define VOXLAB_PROBE_GLSL

#include "voxlab/not_implemented.glsl"

#define PROBE_INPUTS 6
uniform sampler2D u_probe_input[PROBE_INPUTS];

// Input k (a constant) of this pixel's case.
#define PROBE_INPUT(k) texelFetch(u_probe_input[k], ivec2(gl_FragCoord.xy), 0)

layout(location = 0) out vec4 probe_result0;
layout(location = 1) out vec4 probe_result1;
layout(location = 2) out vec4 probe_status;

void probe_write(vec4 first, vec4 second) {
    probe_result0 = first;
    probe_result1 = second;
    probe_status = vec4(voxlab_not_implemented ? 1.0 : 0.0, 0.0, 0.0, 0.0);
}

#endif
