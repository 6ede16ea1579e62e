// voxlab: viewer scripts. The format is in viewer_script.h.
#include "voxlab/viewer_script.h"
#include "voxlab/number_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "json_text.h"
#include "voxlab/error.h"
#include "voxlab/scene.h"

namespace voxlab {

namespace {

// A whole token as a finite number ("12", "-0.5", "+3", "1e-3"); from_chars
// is locale-independent, unlike strtod.
// The start of a number's digits: past one optional '+', which from_chars
// does not take; nullptr for a second sign ("+-3").
const char* afterPlus(const std::string& text) {
    const char* first = text.data();
    if (!text.empty() && *first == '+') {
        ++first;
        if (text.size() > 1 && (*first == '+' || *first == '-')) return nullptr;
    }
    return first;
}

bool parseNumber(const std::string& text, double* out) {
    const char* first = afterPlus(text);
    const char* last = text.data() + text.size();
    if (!first || first == last) return false;
    double value = 0.0;
    if (!parseDoubleExactly(first, last, &value) || !std::isfinite(value)) return false;
    *out = value;
    return true;
}

bool parseInteger(const std::string& text, int* out) {
    const char* first = afterPlus(text);
    const char* last = text.data() + text.size();
    if (!first || first == last) return false;
    int value = 0;
    const auto [end, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || end != last) return false;
    *out = value;
    return true;
}

bool isOneOf(const std::string& text, std::initializer_list<const char*> choices) {
    for (const char* c : choices)
        if (text == c) return true;
    return false;
}

// Splits a line into tokens: blanks separate, double quotes group, `#`
// outside quotes ends the line.
std::vector<std::string> tokenize(const std::string& line, const std::string& where) {
    std::vector<std::string> tokens;
    size_t i = 0;
    while (i < line.size()) {
        const char c = line[i];
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
        } else if (c == '#') {
            break;
        } else {
            std::string token;
            bool quoted = false;
            for (; i < line.size(); ++i) {
                const char d = line[i];
                if (d == '"') quoted = !quoted;
                else if (!quoted && (d == ' ' || d == '\t' || d == '\r' || d == '#')) break;
                else token += d;
            }
            if (quoted) throw Error(where + ": unterminated quote");
            tokens.push_back(token);
        }
    }
    return tokens;
}

// Checks one step's arguments; `step.command` is known to be a command.
class StepChecker {
public:
    explicit StepChecker(const ViewerStep& step) : step_(step) {}

    void check() const {
        const std::string& c = step_.command;
        if (c == "camera") return checkCamera();
        if (!checkWords(c)) checkNumbers(c);
    }

private:
    // The commands whose arguments are paths, names or words; false for another.
    bool checkWords(const std::string& c) const {
        if (c == "load" || c == "scene") exactly(1, "expected 1 path");
        else if (c == "renderer") exactly(1, "expected 1 renderer name");
        else if (c == "implementation") exactly(1, "expected a folder or 'reference'");
        else if (c == "screenshot") exactly(1, "expected 1 output path");
        else if (c == kTransferFunctionName || c == kTransferFunction2DName) exactly(1, "expected 1 path or 'none'");
        else if (c == "quit" || c == "rendering") exactly(0, "expected no arguments");
        else if (c == "right") exactly(1, "expected a renderer name or 'same'");
        else if (c == "press") {
            if (step_.args.empty()) fail("expected one or more keys");
            for (int i = 0; i < int(step_.args.size()); ++i)
                if (!isOneOf(arg(i), {"left", "right", "up", "down", "pageup", "pagedown", "home", "end", "plus", "minus", "p"}))
                    fail("expected keys: left, right, up, down, pageup, pagedown, home, end, plus, minus or p", i);
        } else if (c == "key")
            oneWord("expected a key: left, right, up, down, pageup, pagedown, home, end, plus, minus or p",
                    {"left", "right", "up", "down", "pageup", "pagedown", "home", "end", "plus", "minus", "p"});
        else if (c == "enlarge")
            oneWord("expected axial, coronal, sagittal or off", {"axial", "coronal", "sagittal", "off"});
        else if (c == "interpolation")
            oneWord("expected nearest, trilinear, hardware, bspline or catmull-rom",
                    {"nearest", "trilinear", "hardware", "bspline", "catmull-rom"});
        else if (c == "samples" || c == "skipping" || c == "lod") oneWord("expected on or off", {"on", "off"});
        else if (c == "split") oneWord("expected on, off or difference", {"on", "off", "difference"});
        else if (c == "panel") {
            const std::string msg = "expected a panel (" + viewerPanelList() + ") and on or off";
            exactly(2, msg);
            const std::vector<std::string>& panels = viewerPanels();
            if (std::find(panels.begin(), panels.end(), arg(0)) == panels.end()) fail(msg, 0);
            if (!isOneOf(arg(1), {"on", "off"})) fail(msg, 1);
        } else
            return false;
        return true;
    }

    // The commands whose arguments are numbers (a parameter: a name and a
    // number or true/false).
    void checkNumbers(const std::string& c) const {
        if (c == "ui-scale") {
            const char* msg = "expected 1 number in [0.75, 4]";
            exactly(1, msg);
            const double x = numberAt(0, msg);
            if (!(x >= 0.75 && x <= 4.0)) fail(msg, 0);
        } else if (c == "slide") {
            const char* msg = "expected 1 slide number >= 1";
            exactly(1, msg);
            if (integerAt(0, msg) < 1) fail(msg, 0);
        } else if (c == "divider") {
            const char* msg = "expected 1 number in (0, 1): the divider's place across the window";
            exactly(1, msg);
            const double x = numberAt(0, msg);
            if (!(x > 0.0 && x < 1.0)) fail(msg, 0);
        } else if (c == "param") {
            const char* msg = "expected a name and a number (or true/false)";
            exactly(2, msg);
            double v;
            if (!parseNumber(arg(1), &v) && !isOneOf(arg(1), {"true", "false"})) fail(msg, 1);
        } else if (c == "step") {
            const char* msg = "expected 1 number > 0";
            exactly(1, msg);
            if (!(numberAt(0, msg) > 0.0)) fail(msg, 0);
        } else if (c == "drag") {
            const char* msg = "expected DX DY (pixels per frame) and a number of frames > 0";
            exactly(3, msg);
            numberAt(0, msg), numberAt(1, msg);
            if (integerAt(2, msg) <= 0) fail(msg, 2);
        } else if (c == "drag-plane") {
            const char* msg = "expected a clip plane's number (1..6) and DX DY in window pixels";
            exactly(3, msg);
            const int n = integerAt(0, msg);
            if (n < 1 || n > int(kMaxClipPlanes)) fail(msg, 0);
            numberAt(1, msg), numberAt(2, msg);
        } else if (c == "rotate" || c == "click") {
            const char* msg = "expected 2 numbers";
            exactly(2, msg);
            numberAt(0, msg), numberAt(1, msg);
        } else if (c == "window") {
            const char* msg = "expected 2 numbers LO HI with HI > LO";
            exactly(2, msg);
            if (!(numberAt(1, msg) > numberAt(0, msg))) fail(msg);
        } else if (c == "size") {
            const char* msg = "expected 2 integers > 0";
            exactly(2, msg);
            for (int i = 0; i < 2; ++i)
                if (integerAt(i, msg) <= 0) fail(msg, i);
        } else if (c == "wait") {
            const char* msg = "expected 1 integer >= 0 (frames)";
            exactly(1, msg);
            if (integerAt(0, msg) < 0) fail(msg, 0);
        }
    }

    [[noreturn]] void fail(const std::string& msg) const { failStep(step_, msg); }
    [[noreturn]] void fail(const std::string& msg, int i) const { fail(msg + ", got '" + arg(i) + "'"); }
    const std::string& arg(int i) const { return step_.args[size_t(i)]; }
    void exactly(int n, const std::string& msg) const {
        if (int(step_.args.size()) != n) fail(msg);
    }
    // One argument, one of `words`.
    void oneWord(const std::string& msg, std::initializer_list<const char*> words) const {
        exactly(1, msg);
        if (!isOneOf(arg(0), words)) fail(msg, 0);
    }
    double numberAt(int i, const std::string& msg) const {
        double v;
        if (!parseNumber(arg(i), &v)) fail(msg, i);
        return v;
    }
    int integerAt(int i, const std::string& msg) const {
        int v;
        if (!parseInteger(arg(i), &v)) fail(msg, i);
        return v;
    }

    // "camera" takes SETTING VALUE pairs (pan takes two values).
    void checkCamera() const {
        const int n = int(step_.args.size());
        if (n == 0) fail("expected settings, e.g. 'camera azimuth 40 elevation 25'");
        for (int i = 0; i < n;) {
            const std::string& key = arg(i);
            const int values = key == "pan" ? 2 : 1;
            if (!isOneOf(key, {"azimuth", "elevation", "distance", "fov", "zoom", "pan", "view", "projection"}))
                fail("unknown setting '" + key +
                     "' (expected azimuth, elevation, distance, fov, zoom, pan, view or projection)");
            const bool named = key == "view" || key == "projection";
            const std::string msg = key + ": expected " + (key == "pan" ? "2 numbers" : named ? "a value" : "a number");
            if (i + values >= n) fail(msg);
            if (key == "view") {
                if (!isAxisView(arg(i + 1))) fail("view: expected +x, -x, +y, -y, +z or -z", i + 1);
            } else if (key == "projection") {
                if (!isOneOf(arg(i + 1), {"perspective", "orthographic", "persp", "ortho"}))
                    fail("projection: expected perspective or orthographic", i + 1);
            } else if (key == "distance" || key == "zoom") {
                if (!(numberAt(i + 1, key + ": expected a number > 0") > 0.0))
                    fail(key + ": expected a number > 0", i + 1);
            } else if (key == "fov") {
                const double fov = numberAt(i + 1, "fov: expected degrees in (0, 180)");
                if (!(fov > 0.0 && fov < 180.0)) fail("fov: expected degrees in (0, 180)", i + 1);
            } else {
                for (int k = 1; k <= values; ++k) numberAt(i + k, msg);
            }
            i += 1 + values;
        }
    }

    const ViewerStep& step_;
};

// (kTransferFunction2DName is a stage's, defined in another file: hence const, not constexpr)
const char* const kCommands[] = {
    "load", "scene", "renderer", "param", "step", "interpolation", kTransferFunctionName, kTransferFunction2DName, "camera", "rotate",
    "key", "press", "rendering", "ui-scale", "slide", "enlarge", "window", "samples", "skipping", "lod", "split", "divider", "right", "drag", "drag-plane", "implementation", "panel", "click", "size", "wait", "screenshot", "quit"};

}  // namespace

const std::vector<std::string>& viewerPanels() {
    static const std::vector<std::string> panels = {"slices", kTransferFunctionName, kTransferFunction2DName,
                                                    "profile", "help", "controls"};
    return panels;
}

std::string viewerPanelList() {
    std::string list;
    const std::vector<std::string>& panels = viewerPanels();
    for (std::size_t i = 0; i < panels.size(); ++i)
        list += (i == 0 ? "" : i + 1 == panels.size() ? " or " : ", ") + panels[i];
    return list;
}

std::vector<ViewerStep> parseViewerScriptText(const std::string& text, const std::string& name) {
    std::vector<ViewerStep> steps;
    std::istringstream in(text);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string where = name + ":" + std::to_string(number);
        std::vector<std::string> tokens = tokenize(line, where);
        if (tokens.empty()) continue;
        ViewerStep step;
        step.command = tokens.front();
        step.args.assign(tokens.begin() + 1, tokens.end());
        step.line = number;
        step.file = name;
        bool known = false;
        for (const char* c : kCommands) known = known || step.command == c;
        if (!known) throw Error(where + ": unknown command '" + step.command + "'");
        StepChecker(step).check();
        steps.push_back(std::move(step));
    }
    return steps;
}

std::vector<ViewerStep> parseViewerScript(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open viewer script");
    return parseViewerScriptText(json_text::readCappedText(in, path), path);
}

std::string stepLocation(const ViewerStep& step) { return step.file + ":" + std::to_string(step.line); }

void failStep(const ViewerStep& step, const std::string& message) {
    throw Error(stepLocation(step) + ": " + step.command + ": " + message);
}

const std::string& word(const ViewerStep& step, int i) {
    if (i < 0 || size_t(i) >= step.args.size())
        failStep(step, "missing argument " + std::to_string(i + 1));
    return step.args[size_t(i)];
}

double number(const ViewerStep& step, int i) {
    const std::string& text = word(step, i);
    if (text == "true") return 1.0;
    if (text == "false") return 0.0;
    double v;
    if (!parseNumber(text, &v)) failStep(step, "expected a number, got '" + text + "'");
    return v;
}

int integer(const ViewerStep& step, int i) {
    const std::string& text = word(step, i);
    int v;
    if (!parseInteger(text, &v)) failStep(step, "expected an integer, got '" + text + "'");
    return v;
}

bool onOff(const ViewerStep& step, int i) {
    const std::string& text = word(step, i);
    if (text != "on" && text != "off") failStep(step, "expected on or off, got '" + text + "'");
    return text == "on";
}

std::string dataPath(const ViewerStep& step, int i) {
    const std::string& name = word(step, i);
    try {
        return resolveDataPath(name, std::filesystem::path(step.file).parent_path().string());
    } catch (const Error& e) {
        failStep(step, e.what());
    }
}

void applyCameraStep(const ViewerStep& step, CameraSpec* camera) {
    if (step.command != "camera") failStep(step, "not a camera step");
    for (size_t i = 0; i < step.args.size();) {
        const std::string& key = step.args[i];
        const int at = int(i) + 1;
        if (key == "azimuth" || key == "elevation") {
            if (!camera->view.empty()) {
                axisViewOrbitAngles(camera->view, &camera->azimuth, &camera->elevation);
                camera->view.clear();
            }
            (key == "azimuth" ? camera->azimuth : camera->elevation) = number(step, at);
        } else if (key == "distance") {
            camera->distance = number(step, at);
        } else if (key == "fov") {
            camera->fov = number(step, at);
        } else if (key == "zoom") {
            camera->zoom = number(step, at);
        } else if (key == "pan") {
            camera->pan = glm::dvec2(number(step, at), number(step, at + 1));
            i += 1;
        } else if (key == "view") {
            if (!isAxisView(word(step, at))) failStep(step, "unknown view '" + word(step, at) + "'");
            camera->view = word(step, at);
        } else if (key == "projection") {
            try {
                camera->projection = parseProjection(word(step, at));
            } catch (const Error& e) {
                failStep(step, e.what());
            }
        } else {
            failStep(step, "unknown setting '" + key + "'");
        }
        i += 2;
    }
}

}  // namespace voxlab
