// voxlab CLI: the subcommands. Each returns the process exit code and
// throws voxlab::Error for anything the user should read as one line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "args.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab::cli {

int renderCommand(int argc, char** argv);
int infoCommand(int argc, char** argv);
int listCommand(int argc, char** argv);
int viewCommand(int argc, char** argv);
int compareCommand(int argc, char** argv);
int gradeCommand(int argc, char** argv);
int checkCommand(int argc, char** argv);
int gradeWorkerCommand(int argc, char** argv);
int benchCommand(int argc, char** argv);

// A command a stage brings (framework/stages/STAGE/command.cpp), listed
// after the framework's own by `voxlab help`:
//   VOXLAB_COMMANDS(my_stage) { commands.push_back({"name", "ARGS", "what it does", &run}); }
struct StageCommand {
    const char* name;
    const char* arguments;  // as `voxlab help` shows them: "DATASET"
    const char* summary;
    int (*run)(int argc, char** argv);
};
#define VOXLAB_COMMANDS(stage)                                                \
    namespace voxlab::cli {                                                   \
    void stageCommands_##stage(std::vector<StageCommand>& commands);          \
    }                                                                         \
    void voxlab::cli::stageCommands_##stage(std::vector<voxlab::cli::StageCommand>& commands)
// The stages' commands, in the stages' order.
const std::vector<StageCommand>& stageCommands();

// Options that describe a scene, shared by `render` and `view`.
std::vector<OptionSpec> sceneOptions();
// --max-volume-mib (part of sceneOptions; `info` takes it too), and what it
// does: sets VOXLAB_MAX_VOLUME_MIB, the volume cap of volume.h, after
// checking the value. sceneFromArgs applies it.
OptionSpec volumeCapOption();
void applyVolumeCapOption(const Args& args);
// The dataset named by the first positional argument (found like every
// dataset name, resolveDataPath), loaded under --max-volume-mib.
Volume loadDatasetArgument(const Args& args);
// Builds a scene from `base` when given, else from the scene file named by
// the first positional argument, then applies the flags on top.
Scene sceneFromArgs(const Args& args, const std::string& command, const Scene* base = nullptr);

// The scene that `voxlab render` and the viewer fall back to.
std::string defaultScenePath();

}  // namespace voxlab::cli
