// voxlab GLSL library: a ray walked in runs, so that a stage's plain loop is
// fast without knowing of empty-space skipping.
//
// A stage writes the loop of its handout: every sample of the ray it is
// given, m = 0 .. sample_count(ray) - 1. With skipping on, the entry shader
// does not hand it the whole ray but runs of it, about one brick long
// (samples_per_brick(), voxlab/empty_space.glsl), and asks the brick table
// between two runs where the next run can still matter:
//
//   sample_run(ray, first, end)  samples first .. end - 1 of the ray, as a ray
//                                of their own: t_entry moves to sample
//                                first's start, t_exit to sample end's, so
//                                every sample keeps its place.
//
// The walkers below call the stage's function on each run and combine:
//   largest_over_runs   max over runs in bricks that can beat the maximum (MIP)
//   smallest_over_runs  min over runs in bricks that can undercut it (MinIP)
//   front_to_back_over_runs, back_to_front_over_runs
//                       "over" of runs in visible bricks (compositing; the
//                       colours are premultiplied by opacity)
//   first_hit_over_runs the first run with a hit (first hit)
//   crossing_over_runs  the same for a crossing, each run starting one
//                       sample early so that the crossing test sees the
//                       pair of samples that a whole-ray loop would see
//                       (isosurface)
// A walker exists when its includer names the stage's function first, e.g.
//   #define RUN_LARGEST mip_ray
//   #include "voxlab/runs.glsl"
// With skipping off (a scene's "skip_empty_space": false, and always while
// grading) every walker makes one call with the whole ray, so what is shown
// and graded is exactly the stage's own loop.
#ifndef VOXLAB_RUNS_GLSL
#define VOXLAB_RUNS_GLSL

#include "voxlab/ray.glsl"

Ray sample_run(Ray ray, int first, int end) {
    Ray run = ray;
    run.t_entry = ray.t_entry + float(first) * u_step;
    run.t_exit = ray.t_entry + float(end) * u_step;
    return run;
}

// Where a run that starts at sample `first` ends (exclusive).
int run_end(Ray ray, int first) {
    return min(first + samples_per_brick(), sample_count(ray));
}

#ifdef RUN_LARGEST
float largest_over_runs(Ray ray) {
    if (u_skipping == 0) return RUN_LARGEST(ray);
    // Bricked: start from the bricks in front, so that the walk skips what
    // cannot beat their maximum, as the whole ray's walk would.
    float largest = u_bricked != 0 ? brick_state().r : -3.4e38;
    if (largest >= u_value_range.y) return largest;
    int n = sample_count(ray);
    for (int m = next_sample_above(ray, 0, largest); m < n; m = next_sample_above(ray, m, largest)) {
        int end = run_end(ray, m);
        largest = max(largest, RUN_LARGEST(sample_run(ray, m, end)));
        if (largest >= u_value_range.y) break;  // nothing can be larger
        m = end;
    }
    return largest;
}
#endif

#ifdef RUN_SMALLEST
float smallest_over_runs(Ray ray) {
    if (u_skipping == 0) return RUN_SMALLEST(ray);
    float smallest = u_bricked != 0 ? brick_state().r : 3.4e38;
    if (smallest <= u_value_range.x) return smallest;
    int n = sample_count(ray);
    for (int m = next_sample_below(ray, 0, smallest); m < n; m = next_sample_below(ray, m, smallest)) {
        int end = run_end(ray, m);
        smallest = min(smallest, RUN_SMALLEST(sample_run(ray, m, end)));
        if (smallest <= u_value_range.x) break;  // nothing can be smaller
        m = end;
    }
    return smallest;
}
#endif

// Early termination: a loop over the whole ray stops at the first sample
// where the opacity so far reaches u_early_termination (declared in
// the compositing stage's GLSL), but a run's loop only sees the opacity of its
// own samples. So when a run takes the total past the threshold, the walk
// takes that run again one sample at a time and stops where the whole-ray
// loop would: the image is the same, for at most one run's extra samples.
#ifdef RUN_FRONT_TO_BACK
vec4 front_to_back_over_runs(Ray ray) {
    if (u_skipping == 0 && u_bricked == 0) return RUN_FRONT_TO_BACK(ray);
    // Bricked: start from what the bricks in front composited, so that early
    // termination stops where the whole ray's loop would (with skipping off
    // the brick's part is one run).
    vec4 result = u_bricked != 0 ? brick_state() : vec4(0.0);
    if (result.a >= u_early_termination) return result;
    int n = sample_count(ray);
    int length = samples_per_brick();  // 1 once the threshold is near: see above
    for (int m = next_visible_sample(ray, 0); m < n;) {
        int end = min(m + length, n);
        vec4 total = result + (1.0 - result.a) * RUN_FRONT_TO_BACK(sample_run(ray, m, end));
        if (length > 1 && total.a >= u_early_termination) {
            length = 1;  // take this run again, one sample at a time
            continue;
        }
        result = total;
        if (result.a >= u_early_termination) break;
        m = length > 1 ? next_visible_sample(ray, end) : end;
    }
    return result;
}
#endif

#ifdef RUN_BACK_TO_FRONT
vec4 back_to_front_within_runs(Ray ray) {
    if (u_skipping == 0) return RUN_BACK_TO_FRONT(ray);
    vec4 result = vec4(0.0);
    for (int m = last_visible_sample(ray, sample_count(ray) - 1); m >= 0; m = last_visible_sample(ray, m)) {
        int first = max(m + 1 - samples_per_brick(), 0);
        vec4 front = RUN_BACK_TO_FRONT(sample_run(ray, first, m + 1));
        result = front + (1.0 - front.a) * result;
        m = first - 1;
    }
    return result;
}

// Bricked: this brick's part lies behind what the bricks in front left.
vec4 back_to_front_over_runs(Ray ray) {
    vec4 part = back_to_front_within_runs(ray);
    if (u_bricked == 0) return part;
    vec4 front = brick_state();
    return front + (1.0 - front.a) * part;
}
#endif

#ifdef RUN_FIRST_HIT
bool first_hit_over_runs(Ray ray, out float t, out float value) {
    if (u_skipping == 0) return RUN_FIRST_HIT(ray, t, value);
    int n = sample_count(ray);
    for (int m = next_visible_sample(ray, 0); m < n; m = next_visible_sample(ray, m)) {
        int end = run_end(ray, m);
        if (RUN_FIRST_HIT(sample_run(ray, m, end), t, value)) return true;
        m = end;
    }
    t = 0.0;
    value = 0.0;
    return false;
}
#endif

// A run starts one sample before the visible brick: that sample lies in a
// brick whose values all stay below the isovalue (or ended the previous
// run without a crossing), so it is the "before" of the first pair, as in a
// loop over the whole ray, and never a hit of its own.
#ifdef RUN_CROSSING
bool crossing_over_runs(Ray ray, out float t) {
    // Bricked: the part starts one sample early too, where the brick in
    // front left off (the apron holds it: bricked iso needs a step <= 1).
    if (u_bricked != 0 && voxlab_brick_first_sample > 0) ray = sample_run(ray, -1, sample_count(ray));
    if (u_skipping == 0) return RUN_CROSSING(ray, t);
    int n = sample_count(ray);
    for (int m = next_visible_sample(ray, 0); m < n; m = next_visible_sample(ray, m)) {
        int end = run_end(ray, m);
        if (RUN_CROSSING(sample_run(ray, max(m - 1, 0), end), t)) return true;
        m = end;
    }
    t = 0.0;
    return false;
}
#endif

#endif
