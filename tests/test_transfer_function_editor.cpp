// The transfer-function editor widgets (transfer_function_editor.h), driven
// as a user would: a headless Dear ImGui context (no window, no renderer)
// gets mouse and key input between frames, and the effects on the
// TransferFunction / TransferFunction2D are checked against values computed
// here from the widget's documented geometry: the plot spans the available
// width and options.height pixels from the cursor, inset by
// kTransferFunctionEditorPadding; x is linear in value, y in opacity (1D) or
// gradient magnitude (2D), 0 at the bottom.
//
// Also: undo/redo (the history alone and through its shortcuts), the preset
// list, load/save, the 2D histogram image, and its texture with and without
// a GL context.
#include <gtest/gtest.h>

#ifdef VOXLAB_HAVE_VIEWER

#include "voxlab_gl.h"

#include <imgui.h>

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "voxlab/gl_context.h"
#include "voxlab/transfer_function_editor.h"

namespace voxlab::testing {
namespace {

// ImGui floors the mouse position to whole pixels (in NewFrame), so the
// tests put the mouse on whole pixels and compute what to expect from the
// pixel actually used. Tolerances: the widget maps pixels to data in double,
// from float coordinates of a few hundred pixels (exact to ~3e-5 px): a value
// is expected within a thousandth of a pixel's worth of data units, an
// opacity (stored as float) within 1e-5.
constexpr double kPixelFraction = 1e-3;
constexpr double kAlphaTolerance = 1e-5;

// Key indices the test maps ImGui's named keys to (as a backend would).
constexpr int kDeleteKey = 300, kZKey = 301, kYKey = 302;

// A headless ImGui: one borderless window at the origin holds the widgets.
class HeadlessUi {
public:
    HeadlessUi() {
        context_ = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(800, 700);
        io.IniFilename = nullptr;
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        io.KeyMap[ImGuiKey_Delete] = kDeleteKey;
        io.KeyMap[ImGuiKey_Z] = kZKey;
        io.KeyMap[ImGuiKey_Y] = kYKey;
        io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    }
    ~HeadlessUi() { ImGui::DestroyContext(context_); }
    HeadlessUi(const HeadlessUi&) = delete;
    HeadlessUi& operator=(const HeadlessUi&) = delete;

    template <typename Widgets>
    void frame(Widgets&& widgets) {
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        ImGui::SetNextWindowSize(ImVec2(640, 640));
        ImGui::Begin("test", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                          ImGuiWindowFlags_NoSavedSettings);
        widgets();
        ImGui::End();
        ImGui::Render();
    }

    static void mouseTo(ImVec2 p) { ImGui::GetIO().MousePos = p; }
    static void mouseAway() { ImGui::GetIO().MousePos = ImVec2(-FLT_MAX, -FLT_MAX); }
    static void button(int which, bool down) { ImGui::GetIO().MouseDown[which] = down; }
    static void key(int index, bool down) { ImGui::GetIO().KeysDown[index] = down; }

private:
    ImGuiContext* context_ = nullptr;
};

// The plot rectangle, from the cursor and the width available to a widget.
struct PlotRect {
    ImVec2 min{0, 0}, max{0, 0};

    void capture(float height) {
        const ImVec2 c = ImGui::GetCursorScreenPos();
        const float w = ImGui::GetContentRegionAvail().x, pad = kTransferFunctionEditorPadding;
        min = ImVec2(c.x + pad, c.y + pad);
        max = ImVec2(c.x + w - pad, c.y + pad + height);
    }
    double width() const { return double(max.x) - min.x; }
    double height() const { return double(max.y) - min.y; }
    // The pixel at fractions (fx of the width from the left, fy of the
    // height from the bottom), and the fractions of a pixel.
    ImVec2 at(double fx, double fy) const {
        return ImVec2(std::floor(float(min.x + fx * width())), std::floor(float(max.y - fy * height())));
    }
    double fx(ImVec2 p) const { return (double(p.x) - min.x) / width(); }
    double fy(ImVec2 p) const { return (double(max.y) - p.y) / height(); }
};

ImVec2 offset(ImVec2 p, float dx, float dy) { return ImVec2(std::floor(p.x + dx), std::floor(p.y + dy)); }

ControlPoint point(double value, glm::vec3 color, float alpha) {
    ControlPoint p;
    p.value = value, p.color = color, p.alpha = alpha;
    return p;
}

std::vector<double> valuesOf(const TransferFunction& tf) {
    std::vector<double> out;
    for (const ControlPoint& p : tf.points()) out.push_back(p.value);
    return out;
}

// The 1D editor in a frame, with the plot rectangle it used.
struct Editor1D {
    TransferFunction tf;
    TransferFunctionEditorOptions options;
    int selected = -1;
    PlotRect plot;
    bool changed = false;

    explicit Editor1D(TransferFunction f, glm::dvec2 range) : tf(std::move(f)) { options.range = range; }
    void operator()() {
        plot.capture(options.height);
        changed = TransferFunctionEditor("##tf", &tf, options, &selected);
    }
    bool step(HeadlessUi& ui) {
        ui.frame(*this);
        return changed;
    }
    double range() const { return options.range.y - options.range.x; }
    double valueTolerance() const { return kPixelFraction * range() / plot.width(); }
    // Where a point's handle is: (value, opacity) as plot fractions.
    ImVec2 handle(double value, double alpha) const {
        return plot.at((value - options.range.x) / range(), alpha);
    }
};

// A few frames without input establish the window and the geometry.
template <typename Editor>
void settle(HeadlessUi& ui, Editor& editor) {
    HeadlessUi::mouseAway();
    for (int i = 0; i < 3; ++i) ASSERT_FALSE(editor.step(ui)) << "frame " << i << " without input";
}

TEST(TransferFunctionEditor, ClickOnEmptySpaceAddsAPointThereWithTheInterpolatedColour) {
    HeadlessUi ui;
    Editor1D editor(TransferFunction({point(100, {1, 0, 0}, 0.0f), point(300, {0, 0, 1}, 1.0f)}), {100, 300});
    settle(ui, editor);
    const std::vector<ControlPoint> before = editor.tf.points();

    // Hovering changes nothing.
    const ImVec2 click = editor.plot.at(0.25, 0.7);
    HeadlessUi::mouseTo(click);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(editor.tf.points(), before);

    HeadlessUi::button(0, true);
    EXPECT_TRUE(editor.step(ui));
    ASSERT_EQ(editor.tf.points().size(), 3u);
    const ControlPoint& added = editor.tf.points()[1];
    // At 25% of [100, 300], to the pixel.
    const double t = editor.plot.fx(click);
    ASSERT_NEAR(t, 0.25, 1.0 / editor.plot.width());
    EXPECT_NEAR(added.value, 100.0 + 200.0 * t, editor.valueTolerance());
    EXPECT_NEAR(added.alpha, editor.plot.fy(click), kAlphaTolerance);
    // Red to blue over [100, 300]: a fraction t of the way (float colours).
    EXPECT_NEAR(added.color.r, 1.0 - t, 1e-6);
    EXPECT_NEAR(added.color.g, 0.0, 1e-6);
    EXPECT_NEAR(added.color.b, t, 1e-6);
    EXPECT_EQ(editor.selected, 1);

    HeadlessUi::button(0, false);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::mouseAway();
    for (int i = 0; i < 3; ++i) EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(editor.tf.points().size(), 3u);
}

TEST(TransferFunctionEditor, DraggingMovesThePointByTheMouseAndKeepsThePointsSorted) {
    HeadlessUi ui;
    Editor1D editor(TransferFunction({point(0, {1, 1, 1}, 0.0f), point(300, {1, 0, 0}, 0.2f),
                                      point(600, {0, 1, 0}, 0.5f), point(1000, {0, 0, 1}, 1.0f)}),
                    {0, 1000});
    settle(ui, editor);

    // Grab point 1 a few pixels off its centre: selecting alone changes nothing.
    const ImVec2 grab = offset(editor.handle(300, 0.2), 3.0f, -2.0f);
    HeadlessUi::mouseTo(grab);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(0, true);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(editor.selected, 1);

    // The point follows the mouse's motion, not its position: about +10% of
    // the width and +20% of the height give value ~400 and opacity ~0.4.
    const float dx = std::round(float(0.1 * editor.plot.width())), dy = std::round(float(0.2 * editor.plot.height()));
    HeadlessUi::mouseTo(offset(grab, dx, -dy));
    EXPECT_TRUE(editor.step(ui));
    ASSERT_EQ(editor.tf.points().size(), 4u);
    EXPECT_NEAR(editor.tf.points()[1].value, 300.0 + 1000.0 * dx / editor.plot.width(), editor.valueTolerance());
    EXPECT_NEAR(editor.tf.points()[1].alpha, 0.2 + dy / editor.plot.height(), kAlphaTolerance);

    // Past its right neighbour (600): the points stay sorted, the selection follows.
    const float dx2 = std::round(float(0.4 * editor.plot.width()));
    HeadlessUi::mouseTo(offset(grab, dx2, -dy));
    EXPECT_TRUE(editor.step(ui));
    ASSERT_EQ(editor.tf.points().size(), 4u);
    EXPECT_EQ(editor.selected, 2);
    EXPECT_EQ(editor.tf.points()[1].value, 600.0);
    EXPECT_NEAR(editor.tf.points()[2].value, 300.0 + 1000.0 * dx2 / editor.plot.width(), editor.valueTolerance());
    EXPECT_NEAR(editor.tf.points()[2].alpha, 0.2 + dy / editor.plot.height(), kAlphaTolerance);
    EXPECT_EQ(editor.tf.points()[2].color, glm::vec3(1, 0, 0));

    // Far outside the plot: clamped to the range's end and opacity 1.
    HeadlessUi::mouseTo(offset(editor.plot.max, 80.0f, -editor.plot.max.y + 1.0f));
    EXPECT_TRUE(editor.step(ui));
    EXPECT_EQ(editor.tf.points()[2].value, 1000.0);
    EXPECT_EQ(editor.tf.points()[2].alpha, 1.0f);
    for (std::size_t i = 1; i < editor.tf.points().size(); ++i)
        EXPECT_LE(editor.tf.points()[i - 1].value, editor.tf.points()[i].value);

    // Holding still, then releasing: no change.
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(0, false);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(valuesOf(editor.tf), (std::vector<double>{0, 600, 1000, 1000}));
}

TEST(TransferFunctionEditor, ValueSnapRoundsAddedPoints) {
    HeadlessUi ui;
    Editor1D editor(TransferFunction::ramp(0, 255), {0, 255});
    editor.options.valueSnap = 1.0;
    settle(ui, editor);
    const ImVec2 click = editor.plot.at(0.25, 0.9);  // about 63.75 before snapping
    HeadlessUi::mouseTo(click);
    HeadlessUi::button(0, true);
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(0, false);
    editor.step(ui);
    ASSERT_EQ(editor.tf.points().size(), 3u);
    const double exact = 255.0 * editor.plot.fx(click);
    ASSERT_GT(std::abs(exact - std::round(exact)), 0.01) << "pick a pixel whose value is not already whole";
    EXPECT_EQ(editor.tf.points()[1].value, std::round(exact));
}

TEST(TransferFunctionEditor, MouseWheelZoomsTheOpacityAxis) {
    HeadlessUi ui;
    Editor1D editor(TransferFunction::ramp(0, 100), {0, 100});
    settle(ui, editor);
    HeadlessUi::mouseTo(editor.plot.at(0.5, 0.5));
    editor.step(ui);
    ImGui::GetIO().MouseWheel = 2.0f;  // two notches: zoom 1.25^2, the top at opacity 0.64
    EXPECT_FALSE(editor.step(ui)) << "zooming is not an edit";
    ImGui::GetIO().MouseWheel = 0.0f;
    const ImVec2 click = editor.plot.at(0.6, 0.5);
    HeadlessUi::mouseTo(click);
    editor.step(ui);
    HeadlessUi::button(0, true);
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(0, false);
    editor.step(ui);
    ASSERT_EQ(editor.tf.points().size(), 3u);
    EXPECT_NEAR(editor.tf.points()[1].alpha, 0.64 * editor.plot.fy(click), kAlphaTolerance);
}

TEST(TransferFunctionEditor, RightClickRemovesAPointButNeverLeavesFewerThanTwo) {
    HeadlessUi ui;
    Editor1D editor(TransferFunction({point(0, {1, 1, 1}, 0.0f), point(500, {1, 0, 0}, 0.5f),
                                      point(1000, {0, 0, 1}, 1.0f)}),
                    {0, 1000});
    settle(ui, editor);

    HeadlessUi::mouseTo(offset(editor.handle(500, 0.5), -2.0f, 2.0f));
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(1, true);
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(1, false);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(valuesOf(editor.tf), (std::vector<double>{0, 1000}));

    HeadlessUi::mouseTo(editor.handle(0, 0.0));
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(1, true);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(1, false);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(valuesOf(editor.tf), (std::vector<double>{0, 1000}));

    // A right click on empty space does nothing either.
    HeadlessUi::mouseTo(editor.plot.at(0.5, 0.2));
    editor.step(ui);
    HeadlessUi::button(1, true);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(1, false);
    editor.step(ui);
    EXPECT_EQ(editor.tf.points().size(), 2u);
}

TEST(TransferFunctionEditor, DeleteKeyRemovesTheSelectedPoint) {
    HeadlessUi ui;
    Editor1D editor(TransferFunction({point(0, {1, 1, 1}, 0.0f), point(500, {1, 0, 0}, 0.5f),
                                      point(1000, {0, 0, 1}, 1.0f)}),
                    {0, 1000});
    settle(ui, editor);

    const auto clickAndRelease = [&](ImVec2 p) {
        HeadlessUi::mouseTo(p);
        editor.step(ui);
        HeadlessUi::button(0, true);
        const bool changed = editor.step(ui);
        HeadlessUi::button(0, false);
        editor.step(ui);
        return changed;
    };
    const auto pressDelete = [&] {
        HeadlessUi::key(kDeleteKey, true);
        const bool changed = editor.step(ui);
        HeadlessUi::key(kDeleteKey, false);
        editor.step(ui);
        return changed;
    };

    EXPECT_FALSE(clickAndRelease(editor.handle(1000, 1.0)));
    EXPECT_EQ(editor.selected, 2);
    EXPECT_TRUE(pressDelete());
    EXPECT_EQ(valuesOf(editor.tf), (std::vector<double>{0, 500}));
    EXPECT_EQ(editor.selected, -1);

    EXPECT_FALSE(clickAndRelease(editor.handle(0, 0.0)));
    EXPECT_EQ(editor.selected, 0);
    EXPECT_FALSE(pressDelete());
    EXPECT_EQ(valuesOf(editor.tf), (std::vector<double>{0, 500}));
}

TEST(TransferFunctionEditor, PointsOutsideTheRangeStayPutWhenOnlyClicked) {
    HeadlessUi ui;
    // The range is narrower than the function: both ends sit at the plot's edges.
    Editor1D editor(TransferFunction({point(-50, {1, 1, 1}, 0.3f), point(500, {1, 0, 0}, 0.6f)}), {0, 100});
    settle(ui, editor);
    HeadlessUi::mouseTo(editor.handle(0, 0.3));
    editor.step(ui);
    HeadlessUi::button(0, true);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_FALSE(editor.step(ui)) << "held still";
    HeadlessUi::button(0, false);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_EQ(editor.selected, 0);
    EXPECT_EQ(valuesOf(editor.tf), (std::vector<double>{-50, 500}));
}

// ---------------------------------------------------------------------------
// Undo/redo.

TransferFunction rampTo(double hi) { return TransferFunction::ramp(0, hi); }

TEST(EditHistory, UndoAndRedoRestoreRecordedStates) {
    TransferFunctionHistory history;
    TransferFunction tf = rampTo(1);
    EXPECT_TRUE(history.record(tf));
    EXPECT_FALSE(history.record(rampTo(1))) << "an unchanged state is not a new entry";
    EXPECT_FALSE(history.canUndo(tf));
    history.record(rampTo(2));
    history.record(rampTo(3));
    tf = rampTo(3);

    ASSERT_TRUE(history.undo(&tf));
    EXPECT_EQ(tf.points(), rampTo(2).points());
    ASSERT_TRUE(history.undo(&tf));
    EXPECT_EQ(tf.points(), rampTo(1).points());
    EXPECT_FALSE(history.undo(&tf));
    EXPECT_EQ(tf.points(), rampTo(1).points());

    ASSERT_TRUE(history.redo(&tf));
    EXPECT_EQ(tf.points(), rampTo(2).points());
    // A new edit drops what could have been redone.
    tf = rampTo(7);
    history.record(tf);
    EXPECT_FALSE(history.canRedo());
    EXPECT_FALSE(history.redo(&tf));
    ASSERT_TRUE(history.undo(&tf));
    EXPECT_EQ(tf.points(), rampTo(2).points());
}

TEST(EditHistory, UndoKeepsAnEditThatWasNotRecordedYet) {
    TransferFunctionHistory history;
    TransferFunction tf = rampTo(1);
    history.record(tf);
    tf = rampTo(5);  // edited, never recorded
    EXPECT_TRUE(history.canUndo(tf));
    ASSERT_TRUE(history.undo(&tf));
    EXPECT_EQ(tf.points(), rampTo(1).points());
    ASSERT_TRUE(history.redo(&tf));
    EXPECT_EQ(tf.points(), rampTo(5).points());
}

TEST(EditHistory, DepthIsBounded) {
    EditHistory<int> history(3);
    for (int i = 1; i <= 5; ++i) history.record(i);
    EXPECT_EQ(history.size(), 3u);
    int state = 5;
    EXPECT_TRUE(history.undo(&state));
    EXPECT_TRUE(history.undo(&state));
    EXPECT_EQ(state, 3);
    EXPECT_FALSE(history.undo(&state));
    EXPECT_EQ(state, 3);
}

TEST(EditHistory, WorksOn2DFunctions) {
    TransferFunction2DHistory history;
    Tf2dWidget w;
    w.valueRange = glm::dvec2(10.0);
    TransferFunction2D tf({w});
    history.record(tf);
    tf.widgets()[0].alpha = 0.25f;
    history.record(tf);
    ASSERT_TRUE(history.undo(&tf));
    EXPECT_EQ(tf.widgets()[0].alpha, 1.0f);
    ASSERT_TRUE(history.redo(&tf));
    EXPECT_EQ(tf.widgets()[0].alpha, 0.25f);
}

TEST(EditHistory, CtrlZAndCtrlYUndoAndRedoAnEditorChange) {
    HeadlessUi ui;
    TransferFunctionHistory history;
    Editor1D editor(TransferFunction::ramp(0, 100), {0, 100});
    bool undoRedoChanged = false;
    const auto frame = [&] {
        ui.frame([&] {
            editor();
            undoRedoChanged = TransferFunctionUndoRedo(&history, &editor.tf);
        });
    };
    HeadlessUi::mouseAway();
    for (int i = 0; i < 3; ++i) frame();
    const std::vector<ControlPoint> original = editor.tf.points();

    HeadlessUi::mouseTo(editor.plot.at(0.5, 0.9));
    frame();
    HeadlessUi::button(0, true);
    frame();
    HeadlessUi::button(0, false);
    frame();
    frame();
    const std::vector<ControlPoint> edited = editor.tf.points();
    ASSERT_EQ(edited.size(), 3u);

    ImGui::GetIO().KeyCtrl = true;
    HeadlessUi::key(kZKey, true);
    frame();
    EXPECT_TRUE(undoRedoChanged);
    EXPECT_EQ(editor.tf.points(), original);
    HeadlessUi::key(kZKey, false);
    frame();
    HeadlessUi::key(kYKey, true);
    frame();
    EXPECT_TRUE(undoRedoChanged);
    EXPECT_EQ(editor.tf.points(), edited);
    HeadlessUi::key(kYKey, false);
    ImGui::GetIO().KeyCtrl = false;
    frame();
    EXPECT_FALSE(undoRedoChanged);
}

// ---------------------------------------------------------------------------
// Presets and files.

std::string fileName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

TEST(TransferFunctionFiles, PresetsOfTheDatasetComeFirst) {
    unsetenv("VOXLAB_DATA_PATH");
    for (const std::string name : {"bonsai", "bonsai.nrrd", "/some/where/bonsai.nrrd", "phantom:bonsai:64"}) {
        const std::vector<std::string> presets = transferFunctionPresets(name);
        ASSERT_GE(presets.size(), 8u) << name;
        EXPECT_EQ(fileName(presets[0]), "bonsai.json") << name;
        EXPECT_EQ(std::filesystem::path(presets[0]).parent_path().filename(), "tf") << name;
        // The others follow, sorted by name.
        for (std::size_t i = 2; i < presets.size(); ++i) EXPECT_LT(fileName(presets[i - 1]), fileName(presets[i]));
    }
    const std::vector<std::string> tooth2d = transferFunctionPresets("tooth", "tf2d");
    ASSERT_FALSE(tooth2d.empty());
    EXPECT_EQ(fileName(tooth2d[0]), "tooth.json");
    EXPECT_EQ(std::filesystem::path(tooth2d[0]).parent_path().filename(), "tf2d");
    // No match: everything, sorted.
    const std::vector<std::string> none = transferFunctionPresets("no-such-dataset");
    ASSERT_FALSE(none.empty());
    EXPECT_EQ(fileName(none[0]), "bonsai.json");
}

TEST(TransferFunctionFiles, SaveLoadRoundTripAndErrorsAreMessages) {
    const std::string dir = ::testing::TempDir() + "/tfedit_files";
    std::filesystem::create_directories(dir);
    const TransferFunction tf({point(10, {0.25f, 0.5f, 0.75f}, 0.125f), point(90, {1, 0.5f, 0}, 0.875f)});
    std::string message;
    ASSERT_TRUE(saveTransferFunctionFile(dir + "/a.json", tf, &message)) << message;
    TransferFunction loaded;
    ASSERT_TRUE(loadTransferFunctionFile(dir + "/a.json", &loaded, &message)) << message;
    EXPECT_EQ(loaded.points(), tf.points());  // these values are exact in binary and decimal

    TransferFunction untouched = TransferFunction::ramp(0, 1);
    EXPECT_FALSE(loadTransferFunctionFile(dir + "/missing.json", &untouched, &message));
    EXPECT_EQ(message.rfind("error: ", 0), 0u) << message;
    EXPECT_NE(message.find("missing.json"), std::string::npos) << message;
    EXPECT_EQ(untouched.points(), TransferFunction::ramp(0, 1).points());

    std::ofstream(dir + "/bad.json") << "{\"points\": [{\"value\": 1}]}";
    EXPECT_FALSE(loadTransferFunctionFile(dir + "/bad.json", &untouched, &message));
    EXPECT_NE(message.find("bad.json"), std::string::npos) << message;

    EXPECT_FALSE(saveTransferFunctionFile(dir + "/no/such/folder/x.json", tf, &message));
    EXPECT_EQ(message.rfind("error: ", 0), 0u) << message;

    // 2D, and a relative name found through the dataset search path.
    TransferFunction2D bonsai;
    ASSERT_TRUE(loadTransferFunctionFile("tf2d/bonsai.json", &bonsai, &message)) << message;
    EXPECT_EQ(bonsai.widgets().size(), 3u);
    ASSERT_TRUE(saveTransferFunctionFile(dir + "/b.json", bonsai, &message)) << message;
    TransferFunction2D again;
    ASSERT_TRUE(loadTransferFunctionFile(dir + "/b.json", &again, &message)) << message;
    EXPECT_EQ(again.widgets(), bonsai.widgets());
}

TEST(TransferFunctionFiles, WidgetDrawsWithoutThrowing) {
    HeadlessUi ui;
    TransferFunction tf = TransferFunction::ramp(0, 1);
    TransferFunction2D tf2d;
    std::string path = "tf/bonsai.json", message = "error: an earlier failure", path2d, message2d;
    bool changed = true;
    for (int i = 0; i < 3; ++i)
        ui.frame([&] {
            changed = TransferFunctionFiles("preset", &tf, "bonsai", &path, &message);
            changed |= TransferFunction2DFiles("##2d", &tf2d, "bonsai", &path2d, &message2d);
        });
    EXPECT_FALSE(changed);
    EXPECT_GT(ImGui::GetDrawData()->TotalVtxCount, 0);
}

// ---------------------------------------------------------------------------
// The 2D editor.

// 50 x 20 bins over value [0, 100] and gradient [0, 10], some of them empty.
Histogram2D testHistogram() {
    Histogram2D h;
    h.valueLo = 0, h.valueHi = 100, h.gradientMax = 10, h.valueBins = 50, h.gradientBins = 20;
    h.counts.resize(1000);
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 50; ++x) h.counts[std::size_t(y * 50 + x)] = std::uint64_t((x * 7 + y * 13) % 23) * 40;
    return h;
}

struct Editor2D {
    TransferFunction2D tf;
    Histogram2D histogram = testHistogram();
    TransferFunction2DEditorOptions options;
    int selected = -1;
    PlotRect plot;
    bool changed = false;

    void operator()() {
        plot.capture(options.height);
        changed = TransferFunction2DEditor("##tf2d", &tf, histogram, &selected, options);
    }
    bool step(HeadlessUi& ui) {
        ui.frame(*this);
        return changed;
    }
    // The screen point of (value, gradient magnitude).
    ImVec2 at(double f, double g) const { return plot.at(f / 100.0, g / 10.0); }
    double valueTolerance() const { return kPixelFraction * 100.0 / plot.width(); }
    double gradientTolerance() const { return kPixelFraction * 10.0 / plot.height(); }
};

Tf2dWidget box(glm::dvec2 value, glm::dvec2 gradient) {
    Tf2dWidget w;
    w.kind = Tf2dWidget::Kind::Box;
    w.valueRange = value, w.gradientRange = gradient, w.alpha = 0.5f;
    return w;
}

TEST(TransferFunction2DEditor, DoubleClickAddsATriangleThatCanBeMovedResizedAndRemoved) {
    HeadlessUi ui;
    Editor2D editor;
    settle(ui, editor);

    const ImVec2 click = editor.at(30, 5);
    HeadlessUi::mouseTo(click);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(0, true);
    EXPECT_FALSE(editor.step(ui)) << "a single click on empty space adds nothing";
    HeadlessUi::button(0, false);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::button(0, true);
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(0, false);
    EXPECT_FALSE(editor.step(ui));
    ASSERT_EQ(editor.tf.widgets().size(), 1u);
    const Tf2dWidget added = editor.tf.widgets()[0];
    EXPECT_EQ(added.kind, Tf2dWidget::Kind::Triangle);
    EXPECT_NEAR(added.valueRange.x, 100.0 * editor.plot.fx(click), editor.valueTolerance());
    EXPECT_GT(added.radius, 0.0);
    EXPECT_EQ(editor.selected, 0);

    // Drag the apex (at gradient 0) by +20% of the width and up: the value
    // follows the horizontal motion only.
    const ImVec2 apex = offset(editor.at(added.valueRange.x, 0), 2.0f, -3.0f);
    HeadlessUi::mouseTo(apex);
    editor.step(ui);
    HeadlessUi::button(0, true);
    EXPECT_FALSE(editor.step(ui));
    HeadlessUi::mouseTo(offset(apex, 0.0f, -30.0f));
    EXPECT_FALSE(editor.step(ui)) << "a triangle moves along the value axis only";
    const float dx = std::round(float(0.2 * editor.plot.width()));
    HeadlessUi::mouseTo(offset(apex, dx, -40.0f));
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(0, false);
    editor.step(ui);
    const double value = editor.tf.widgets()[0].valueRange.x;
    EXPECT_NEAR(value, added.valueRange.x + 100.0 * dx / editor.plot.width(), editor.valueTolerance());
    EXPECT_EQ(editor.tf.widgets()[0].radius, added.radius);

    // Drag the top right corner (value + radius * gradientMax, gradientMax)
    // right by dx2 pixels: the half-width at the top grows by
    // 100 dx2 / width value units, the radius by that / gradientMax.
    const ImVec2 corner = offset(editor.at(value + added.radius * 10.0, 10.0), 1.0f, 2.0f);
    HeadlessUi::mouseTo(corner);
    editor.step(ui);
    HeadlessUi::button(0, true);
    EXPECT_FALSE(editor.step(ui));
    const float dx2 = std::round(float(0.16 * editor.plot.width()));
    HeadlessUi::mouseTo(offset(corner, dx2, 0.0f));
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(0, false);
    editor.step(ui);
    const double expectedRadius = (added.radius * 10.0 + 100.0 * dx2 / editor.plot.width()) / 10.0;
    EXPECT_NEAR(expectedRadius, 2.0, 0.1);
    EXPECT_NEAR(editor.tf.widgets()[0].radius, expectedRadius, editor.valueTolerance() / 10.0);
    EXPECT_EQ(editor.tf.widgets()[0].valueRange.x, value);

    // Right click inside it (half way up, on its centre line) removes it.
    HeadlessUi::mouseTo(editor.at(value + 1.0, 5.0));
    editor.step(ui);
    HeadlessUi::button(1, true);
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::button(1, false);
    editor.step(ui);
    EXPECT_TRUE(editor.tf.widgets().empty());
    EXPECT_EQ(editor.selected, -1);
}

TEST(TransferFunction2DEditor, BoxesMoveAndResizeInsideTheDomain) {
    HeadlessUi ui;
    Editor2D editor;
    editor.tf = TransferFunction2D({box({20, 40}, {2, 6})});
    settle(ui, editor);

    // Drags from one pixel to another; returns whether only the motion
    // changed the function, and the motion in data units.
    glm::dvec2 motion{0.0};
    const auto drag = [&](ImVec2 from, ImVec2 to) {
        HeadlessUi::mouseTo(from);
        editor.step(ui);
        HeadlessUi::button(0, true);
        const bool pressChanged = editor.step(ui);
        HeadlessUi::mouseTo(to);
        const bool changed = editor.step(ui);
        HeadlessUi::button(0, false);
        editor.step(ui);
        motion = {100.0 * (double(to.x) - from.x) / editor.plot.width(),
                  10.0 * (double(from.y) - to.y) / editor.plot.height()};
        return !pressChanged && changed;
    };
    const auto expectBox = [&](glm::dvec2 v, glm::dvec2 g) {
        const Tf2dWidget& w = editor.tf.widgets().at(0);
        EXPECT_NEAR(w.valueRange.x, v.x, editor.valueTolerance());
        EXPECT_NEAR(w.valueRange.y, v.y, editor.valueTolerance());
        EXPECT_NEAR(w.gradientRange.x, g.x, editor.gradientTolerance());
        EXPECT_NEAR(w.gradientRange.y, g.y, editor.gradientTolerance());
    };

    // Move by about (+10, +1) from inside: both ranges shift by the motion.
    EXPECT_TRUE(drag(editor.at(30, 4), editor.at(40, 5)));
    EXPECT_EQ(editor.selected, 0);
    const glm::dvec2 v1 = glm::dvec2(20, 40) + motion.x, g1 = glm::dvec2(2, 6) + motion.y;
    expectBox(v1, g1);
    // Corner (v1, g1) dragged by about (+30, +2): only that corner moves.
    const ImVec2 corner(std::floor(editor.plot.min.x + float((v1.y / 100.0) * editor.plot.width())),
                        std::floor(editor.plot.max.y - float((g1.y / 10.0) * editor.plot.height())));
    EXPECT_TRUE(drag(corner, editor.at(80, 9)));
    const glm::dvec2 v2(v1.x, v1.y + motion.x), g2(g1.x, g1.y + motion.y);
    expectBox(v2, g2);
    // A move that would leave the domain stops at its edge.
    EXPECT_TRUE(drag(editor.at(50, 5), editor.at(100, 5)));
    ASSERT_GT(v2.y + motion.x, 100.0);
    expectBox(v2 + (100.0 - v2.y), g2);
    // A corner cannot pass the opposite one: (v0, g0) dragged beyond (v1, g1).
    EXPECT_TRUE(drag(editor.at(50, 3), editor.at(100, 10)));
    const Tf2dWidget& w = editor.tf.widgets()[0];
    EXPECT_LE(w.valueRange.x, w.valueRange.y);
    EXPECT_LE(w.gradientRange.x, w.gradientRange.y);

    // Delete removes the selected box.
    HeadlessUi::key(kDeleteKey, true);
    EXPECT_TRUE(editor.step(ui));
    HeadlessUi::key(kDeleteKey, false);
    EXPECT_FALSE(editor.step(ui));
    EXPECT_TRUE(editor.tf.widgets().empty());
}

TEST(TransferFunction2DEditor, HistogramImageFollowsTheLogOfTheCounts) {
    const Histogram2D h = testHistogram();
    const std::vector<std::uint8_t> image = histogram2DImage(h);
    ASSERT_EQ(image.size(), h.counts.size());
    const std::uint64_t largest = 22 * 40;  // (x*7 + y*13) % 23 reaches 22
    for (std::size_t i = 0; i < image.size(); ++i) {
        // The documented mapping, 255 log(1 + c) / log(1 + max); +-1 for the rounding of a double.
        const double expected = 255.0 * std::log(1.0 + double(h.counts[i])) / std::log(1.0 + double(largest));
        EXPECT_NEAR(double(image[i]), expected, 0.5 + 1e-9) << "bin " << i;
        if (h.counts[i] == 0) {
            EXPECT_EQ(image[i], 0);
        }
        if (h.counts[i] == largest) {
            EXPECT_EQ(image[i], 255);
        }
    }
    const std::vector<std::uint8_t> linear = histogram2DImage(h, false);
    for (std::size_t i = 0; i < image.size(); ++i)
        EXPECT_NEAR(double(linear[i]), 255.0 * double(h.counts[i]) / double(largest), 0.5 + 1e-9);
    // Empty and inconsistent histograms give black images, not errors.
    Histogram2D empty = h;
    std::fill(empty.counts.begin(), empty.counts.end(), 0);
    for (std::uint8_t v : histogram2DImage(empty)) EXPECT_EQ(v, 0);
    Histogram2D broken = h;
    broken.counts.resize(10);
    for (std::uint8_t v : histogram2DImage(broken)) EXPECT_EQ(v, 0);
}

// Must run before any GL context exists in this process (gtest keeps the
// order of a file's tests unless shuffled): the editor draws its histogram
// without GL when there is no OpenGL3 backend, and the texture helper says
// "none" instead of calling through null function pointers.
TEST(TransferFunction2DEditor, DrawsWithoutAGlContext) {
    if (voxlab_gl.GenTextures) GTEST_SKIP() << "a GL context was created earlier in this process";
    const Histogram2D h = testHistogram();
    EXPECT_EQ(histogram2DTexture(h), 0u);
    HeadlessUi ui;
    Editor2D editor;
    editor.tf = TransferFunction2D({box({20, 40}, {2, 6})});
    HeadlessUi::mouseTo(editor.at(50, 5));  // with a tooltip
    for (int i = 0; i < 3; ++i) EXPECT_FALSE(editor.step(ui));
    // The histogram's cells are drawn as rectangles: many more vertices than
    // the widgets alone need (each nonzero cell is one quad, 4 vertices).
    int nonzero = 0;
    for (std::uint64_t c : h.counts) nonzero += c > 0;
    EXPECT_GT(ImGui::GetDrawData()->TotalVtxCount, 4 * nonzero);
}

TEST(TransferFunction2DEditor, HistogramTextureIsUploadedOnceAndUpdatedWhenTheCountsChange) {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    Histogram2D h = testHistogram();
    const auto readBack = [&](unsigned texture) {
        std::vector<std::uint8_t> pixels(h.counts.size(), 7);
        glBindTexture(GL_TEXTURE_2D, texture);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_UNSIGNED_BYTE, pixels.data());
        glBindTexture(GL_TEXTURE_2D, 0);
        return pixels;
    };
    const unsigned texture = histogram2DTexture(h);
    ASSERT_NE(texture, 0u);
    EXPECT_TRUE(glIsTexture(texture));
    EXPECT_EQ(histogram2DTexture(h), texture) << "the same histogram is served from the cache";
    EXPECT_EQ(readBack(texture), histogram2DImage(h));

    h.counts[0] = 100000;  // recomputed in place: same address and size, new contents
    EXPECT_EQ(histogram2DTexture(h), texture);
    const std::vector<std::uint8_t> updated = readBack(texture);
    EXPECT_EQ(updated, histogram2DImage(h));
    EXPECT_EQ(updated[0], 255);

    const unsigned linear = histogram2DTexture(h, false);
    EXPECT_NE(linear, texture);
    EXPECT_EQ(readBack(linear), histogram2DImage(h, false));

    releaseTransferFunctionEditorTextures();
    EXPECT_FALSE(glIsTexture(texture));
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace voxlab::testing

#else

TEST(TransferFunctionEditor, NeedsTheViewer) { GTEST_SKIP() << "built without the viewer (VOXLAB_WITH_VIEWER=OFF)"; }

#endif
