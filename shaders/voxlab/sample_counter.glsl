// voxlab GLSL library: counting the samples a ray takes (for `voxlab bench`).
//
// When the engine bakes u_count_samples = 1, sample_position() counts every
// sample a renderer asks for, and finish() writes that count into the red
// channel instead of the pixel's colour; the engine adds the counts up
// (RenderEngine::countSamples). With u_count_samples = 0 (every normal
// render) the counting is compiled away.
#ifndef VOXLAB_SAMPLE_COUNTER_GLSL
#define VOXLAB_SAMPLE_COUNTER_GLSL

uniform int u_count_samples;
int voxlab_samples_taken = 0;

#endif
