// voxlab viewer: running a viewer script (voxlab/viewer_script.h), one step
// per frame, so that CI and the README's screenshots drive the real window.
#pragma once

#include <string>
#include <vector>

#include "viewer_state.h"
#include "voxlab/viewer_script.h"

struct GLFWwindow;

namespace voxlab::viewer {

class ScriptRunner {
public:
    enum Progress { Continue, Done };
    explicit ScriptRunner(const std::string& path);  // parses it all first: errors before any window work
    // Applies the next step (or keeps waiting). Throws voxlab::Error naming
    // the script's file and line when a step fails.
    Progress step(State& s, GLFWwindow* window);

private:
    Progress drag(State& s);
    Progress press(State& s, GLFWwindow* window, const ViewerStep& st);
    Progress rendering(State& s, const ViewerStep& st);
    void noteFrame(const State& s);
    Progress finished(const State& s) const;  // Done, after a line on the frames drawn while bands rendered  // the time between frames while an image renders in bands
    Clock::time_point lastFrame_{};
    std::vector<double> bandFrameMs_;
    int waitedFrames_ = 0;
    std::vector<ViewerStep> steps_;
    std::size_t next_ = 0;
    int waitFrames_ = 0;
    int heldKey_ = 0;  // a GLFW key a `key` step pressed, released at the next step
    // A `drag` in progress: frames left, pixels per frame, render times seen.
    int dragFrames_ = 0;
    bool settling_ = false;
    double dragDx_ = 0, dragDy_ = 0;
    std::vector<double> dragTimes_;
    std::string dragLevel_;  // the coarse level the drag showed ("level 1, GPU filtering"), or ""
    int refinements_ = 0;  // the last refinement step seen while settling
    std::string dragSize_;
};

}  // namespace voxlab::viewer
