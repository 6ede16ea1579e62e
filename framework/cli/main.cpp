// voxlab: the single entry point. `voxlab COMMAND [options]`.
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/untrusted_text.h"

namespace {

void usage(std::ostream& out) {
    using voxlab::cli::StageCommand;
    out << "usage: voxlab COMMAND [options]\n\n"
           "commands:\n"
           "  view [DATASET|SCENE]   open the interactive viewer (default when a display is present)\n"
           "  render [SCENE]         render one image headless to PNG\n"
           "  info DATASET           dimensions, type, spacing, value range and histogram of a volume\n"
           "  list                   the renderers and their parameters\n"
           "  compare A.png B.png    difference, PSNR and SSIM between two images\n"
           "  bench [SCENE]          time a scene frame after frame (median ms/frame, samples/s)\n"
           "  check [--stage S]      check your assignments/ against the expected images\n"
           "  grade --submission DIR grade a submission (or --batch DIR, a class) against the reference\n";
    for (const StageCommand& c : voxlab::cli::stageCommands()) {
        const std::string usage = std::string(c.name) + " " + c.arguments;
        out << "  " << usage << std::string(usage.size() < 23 ? 23 - usage.size() : 1, ' ') << c.summary << "\n";
    }
    out << "  help                   this text\n\n"
           "Every command takes --help. Datasets are files (.nrrd .nhdr .fld .dat), DICOM series (a folder\n"
           "or one of its files) or phantoms such as phantom:marschner-lobb:64; bare names are also looked\n"
           "up in the project's datasets/ folder.\n";
}

}  // namespace

namespace voxlab::cli {

#define VOXLAB_STAGE_COMMANDS(stage) void stageCommands_##stage(std::vector<StageCommand>& commands);
#include "voxlab_stage_commands.inc"
#undef VOXLAB_STAGE_COMMANDS

const std::vector<StageCommand>& stageCommands() {
    static const std::vector<StageCommand> commands = [] {
        std::vector<StageCommand> all;
#define VOXLAB_STAGE_COMMANDS(stage) stageCommands_##stage(all);
#include "voxlab_stage_commands.inc"
#undef VOXLAB_STAGE_COMMANDS
        return all;
    }();
    return commands;
}

}  // namespace voxlab::cli

int main(int argc, char** argv) {
    using namespace voxlab::cli;
    const std::string command = argc > 1 ? argv[1] : "";
    try {
        if (command.empty()) {
            if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY")) return viewCommand(argc, argv);
            usage(std::cout);
            return 0;
        }
        if (command == "render") return renderCommand(argc, argv);
        if (command == "info") return infoCommand(argc, argv);
        if (command == "list") return listCommand(argc, argv);
        if (command == "view") return viewCommand(argc, argv);
        if (command == "compare") return compareCommand(argc, argv);
        if (command == "grade") return gradeCommand(argc, argv);
        if (command == "bench") return benchCommand(argc, argv);
        for (const StageCommand& c : stageCommands())
            if (command == c.name) return c.run(argc, argv);
        if (command == "check") return checkCommand(argc, argv);
        if (command == "grade-worker") return gradeWorkerCommand(argc, argv);
        if (command == "help" || command == "--help" || command == "-h") {
            usage(std::cout);
            return 0;
        }
        std::cerr << "voxlab: unknown command '" << voxlab::terminalLine(command, 200) << "' (try voxlab help)\n";
        return 2;
    } catch (const voxlab::Error& e) {
        // Messages may quote a file's name or a compiler's output: no control bytes reach the terminal.
        std::cerr << "voxlab: " << voxlab::terminalText(e.what(), voxlab::kMaxLogBytes) << "\n";
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "voxlab: out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "voxlab: internal error: " << voxlab::terminalText(e.what(), voxlab::kMaxLogBytes) << "\n";
        return 1;
    }
}
