// voxlab: undo/redo buttons and shortcuts for the transfer-function editors
// (the history itself, EditHistory, is a template in transfer_function_editor.h).
#include <imgui.h>

#include "transfer_function_editor_drawing.h"
#include "voxlab/transfer_function_editor.h"

namespace voxlab {

namespace {

template <typename State>
bool undoRedo(EditHistory<State>* history, State* state) {
    ImGui::PushID(history);
    const ImGuiIO& io = ImGui::GetIO();
    // An edit is over when nothing is held: record its result (a no-op when
    // nothing changed since the last record).
    const bool editing = ImGui::IsAnyItemActive() || ImGui::IsAnyMouseDown();
    if (!editing) history->record(*state);

    bool undo = false, redo = false;
    ImGui::BeginDisabled(!history->canUndo(*state));
    undo = ImGui::Button("undo");
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("Ctrl+Z");
    ImGui::SameLine();
    ImGui::BeginDisabled(!history->canRedo());
    redo = ImGui::Button("redo");
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("Ctrl+Y or Ctrl+Shift+Z");

    if (!editing && io.KeyCtrl && !io.WantTextInput && ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows)) {
        if (tf_editor::keyPressed(ImGuiKey_Z)) (io.KeyShift ? redo : undo) = true;
        if (tf_editor::keyPressed(ImGuiKey_Y)) redo = true;
    }
    bool changed = false;
    if (undo) changed = history->undo(state);
    else if (redo) changed = history->redo(state);
    ImGui::PopID();
    return changed;
}

}  // namespace

bool TransferFunctionUndoRedo(TransferFunctionHistory* history, TransferFunction* tf) { return undoRedo(history, tf); }

bool TransferFunctionUndoRedo(TransferFunction2DHistory* history, TransferFunction2D* tf) {
    return undoRedo(history, tf);
}

}  // namespace voxlab
