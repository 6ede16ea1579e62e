// voxlab: transfer-function presets and files for the editors: the preset
// list of a dataset, load and save, and the widget that offers them.
#include <imgui.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "transfer_function_editor_drawing.h"
#include "voxlab/atomic_file.h"
#include "voxlab/error.h"
#include "voxlab/scene.h"
#include "voxlab/transfer_function_editor.h"

namespace voxlab {

namespace fs = std::filesystem;

namespace {

// "bonsai" from "bonsai", "bonsai.nrrd", "/data/bonsai.nrrd" or "phantom:bonsai:64".
std::string datasetStem(const std::string& name) {
    const std::string phantom = "phantom:";
    if (name.rfind(phantom, 0) == 0) {
        const std::string rest = name.substr(phantom.size());
        return rest.substr(0, rest.find(':'));
    }
    const std::string file = fs::path(name).filename().string();
    return file.substr(0, file.find('.'));
}

// The dataset folders, in search order: $VOXLAB_DATA_PATH, then datasets/.
std::vector<fs::path> datasetFolders() {
    std::vector<fs::path> folders;
    const char* env = std::getenv("VOXLAB_DATA_PATH");
    const std::string dataPath = env ? env : "";
    std::size_t start = 0;
    while (start <= dataPath.size()) {
        std::size_t end = dataPath.find(':', start);
        if (end == std::string::npos) end = dataPath.size();
        if (end > start) folders.emplace_back(dataPath.substr(start, end - start));
        start = end + 1;
    }
    folders.push_back(fs::path(projectRoot()) / "datasets");
    return folders;
}

template <typename Function>
bool loadInto(const std::string& path, Function* tf, std::string* message) {
    try {
        if (path.empty()) throw Error("no file name given");
        const std::string found = resolveDataPath(path);
        *tf = Function::load(found);
        *message = "loaded " + found;
        return true;
    } catch (const std::exception& e) {
        *message = std::string("error: ") + e.what();
        return false;
    }
}

template <typename Function>
bool saveFrom(const std::string& path, const Function& tf, std::string* message) {
    try {
        if (path.empty()) throw Error("no file name given");
        // Atomic: a failed save (a full disk, a missing folder) keeps the
        // preset that was there, and says why.
        writeFileAtomically(path, tf.toJson().dump(2) + "\n");
        *message = "saved " + path;
        return true;
    } catch (const std::exception& e) {
        *message = std::string("error: ") + e.what();
        return false;
    }
}

// The preset list of a dataset, listed again each time the combo opens.
const std::vector<std::string>& cachedPresets(const std::string& datasetName, const std::string& folder, bool refresh) {
    static std::map<std::pair<std::string, std::string>, std::vector<std::string>> cache;
    const auto key = std::make_pair(datasetName, folder);
    auto it = cache.find(key);
    if (it == cache.end() || refresh)
        it = cache.insert_or_assign(key, transferFunctionPresets(datasetName, folder)).first;
    return it->second;
}

template <typename Function>
bool filesWidget(const char* label, Function* tf, const std::string& datasetName, std::string* path,
                 std::string* message, const std::string& folder) {
    ImGui::PushID(label);
    bool changed = false;
    const std::string stem = datasetStem(datasetName);
    const ImGuiStyle& style = ImGui::GetStyle();

    // Presets: this dataset's first, then the others after a separator.
    const std::string current = fs::path(*path).filename().string();
    const std::string title = tf_editor::visibleLabel(label);
    const std::string preview = current.empty() ? "(choose a preset)" : current;
    const float labelWidth = title.empty() ? 0.0f : ImGui::CalcTextSize(title.c_str()).x + style.ItemInnerSpacing.x;
    ImGui::SetNextItemWidth(std::max(60.0f, ImGui::GetContentRegionAvail().x - labelWidth));
    if (ImGui::BeginCombo(title.empty() ? "##preset" : title.c_str(), preview.c_str())) {
        const auto& presets = cachedPresets(datasetName, folder, ImGui::IsWindowAppearing());
        bool ownGroup = true;
        for (std::size_t i = 0; i < presets.size(); ++i) {
            const fs::path p(presets[i]);
            const std::string name = p.filename().string();
            const bool own = !stem.empty() && name.rfind(stem, 0) == 0;
            if (ownGroup && !own) {
                if (i > 0) ImGui::Separator();
                ownGroup = false;
            }
            ImGui::PushID(int(i));
            if (ImGui::Selectable(p.stem().string().c_str(), presets[i] == *path)) {
                Function loaded;
                if (loadInto(presets[i], &loaded, message)) *tf = std::move(loaded), *path = presets[i], changed = true;
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", presets[i].c_str());
            ImGui::PopID();
        }
        if (presets.empty()) ImGui::TextDisabled("no presets in %s/ of the dataset folders", folder.c_str());
        ImGui::EndCombo();
    }

    // A path, and load/save.
    const float buttonsWidth =
        ImGui::CalcTextSize("loadsave").x + 4.0f * style.FramePadding.x + 2.0f * style.ItemSpacing.x;
    ImGui::SetNextItemWidth(std::max(60.0f, ImGui::GetContentRegionAvail().x - buttonsWidth));
    const bool entered = tf_editor::inputText("##path", path, ImGuiInputTextFlags_EnterReturnsTrue);
    if (ImGui::IsItemHovered() && !path->empty()) ImGui::SetTooltip("%s", path->c_str());
    ImGui::SameLine();
    if (ImGui::Button("load") || entered) {
        Function loaded;
        if (loadInto(*path, &loaded, message)) *tf = std::move(loaded), changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("save")) {
        // Overwriting (a bundled preset, say) takes a second click.
        std::error_code ec;
        if (!path->empty() && fs::exists(*path, ec)) ImGui::OpenPopup("##overwrite");
        else saveFrom(*path, *tf, message);
    }
    if (ImGui::BeginPopup("##overwrite")) {
        ImGui::Text("%s exists.", fs::path(*path).filename().string().c_str());
        if (ImGui::Button("overwrite")) saveFrom(*path, *tf, message), ImGui::CloseCurrentPopup();
        ImGui::SameLine();
        if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
    if (!message->empty()) {
        const bool error = message->rfind("error", 0) == 0;
        ImGui::PushStyleColor(ImGuiCol_Text, error ? ImVec4(1.0f, 0.45f, 0.35f, 1.0f)
                                                   : ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("%s", message->c_str());
        ImGui::PopStyleColor();
    }
    ImGui::PopID();
    return changed;
}

}  // namespace

std::vector<std::string> transferFunctionPresets(const std::string& datasetName, const std::string& folder) {
    const std::string stem = datasetStem(datasetName);
    std::vector<std::pair<std::string, std::string>> own, others;  // (file name, path)
    std::set<std::string> seen;
    for (const fs::path& base : datasetFolders()) {
        std::error_code ec;
        const fs::path dir = base / folder;
        if (!fs::is_directory(dir, ec)) continue;
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
            if (entry.path().extension() != ".json" || !entry.is_regular_file(ec)) continue;
            const std::string canonical = fs::weakly_canonical(entry.path(), ec).string();
            if (!seen.insert(canonical.empty() ? entry.path().string() : canonical).second) continue;
            const std::string name = entry.path().filename().string();
            const bool match = !stem.empty() && name.rfind(stem, 0) == 0;
            (match ? own : others).emplace_back(name, entry.path().string());
        }
    }
    std::vector<std::string> out;
    for (auto* group : {&own, &others}) {
        std::stable_sort(group->begin(), group->end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& item : *group) out.push_back(item.second);
    }
    return out;
}

bool loadTransferFunctionFile(const std::string& path, TransferFunction* tf, std::string* message) {
    return loadInto(path, tf, message);
}
bool loadTransferFunctionFile(const std::string& path, TransferFunction2D* tf, std::string* message) {
    return loadInto(path, tf, message);
}
bool saveTransferFunctionFile(const std::string& path, const TransferFunction& tf, std::string* message) {
    return saveFrom(path, tf, message);
}
bool saveTransferFunctionFile(const std::string& path, const TransferFunction2D& tf, std::string* message) {
    return saveFrom(path, tf, message);
}

bool TransferFunctionFiles(const char* label, TransferFunction* tf, const std::string& datasetName, std::string* path,
                           std::string* message) {
    return filesWidget(label, tf, datasetName, path, message, kTransferFunctionName);
}

bool TransferFunction2DFiles(const char* label, TransferFunction2D* tf, const std::string& datasetName,
                             std::string* path, std::string* message) {
    return filesWidget(label, tf, datasetName, path, message, kTransferFunction2DName);
}

}  // namespace voxlab
