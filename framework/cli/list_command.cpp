// voxlab list: the registered renderers and their declared parameters, or
// (--checks) the function checks each stage folder registers, or
// (--sections) the scene sections stages bring.
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "voxlab/function_checks.h"
#include "voxlab/renderer.h"
#include "voxlab/scene_section.h"
#include "voxlab/stage_registry.h"

namespace voxlab::cli {

int listCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = {{"help", "", "show this help"},
                                           {"checks", "", "list the function checks instead (name, stage, what)"},
                                           {"sections", "", "list the scene sections stages bring, as a scene writes them"}};
    const Args args(specs, argc, argv, 2, "list");
    if (auto status = usageExit(args, false,
                                "usage: voxlab list [--checks | --sections]\n\nNames every renderer with a one-line description and "
                                "its parameters;\nwith --checks, every function check a manifest may name, its stage "
                                "and what it runs;\nwith --sections, the parts of a scene file that stages bring "
                                "(voxlab/scene.h has the rest).\n\n",
                                specs))
        return *status;
    if (args.has("checks")) {
        for (const FunctionCheckInfo& c : functionChecks())
            std::printf("%-28s %-16s %s\n", c.name.c_str(), c.stage.c_str(), c.description.c_str());
        return 0;
    }
    if (args.has("sections")) {
        for (const SceneSection& section : stageSceneSections()) std::printf("%s\n\n", section.doc);
        return 0;
    }
    for (const auto& r : rendererRegistry().all()) {
        std::printf("%-10s %s\n", r->id().c_str(), r->description().c_str());
        for (const ParameterSpec& p : r->parameters()) {
            if (p.dataUnits)
                std::printf("  %-22s %s in data units, default %g of the value range: %s\n", p.name.c_str(),
                            parameterTypeName(p.type), p.defaultValue, p.description.c_str());
            else if (p.dataSpan)
                std::printf("  %-22s %s in data units, default %g of the value range's width: %s\n", p.name.c_str(),
                            parameterTypeName(p.type), p.defaultValue, p.description.c_str());
            else
                std::printf("  %-22s %s in [%g, %g], default %g: %s\n", p.name.c_str(), parameterTypeName(p.type),
                            p.minValue, p.maxValue, p.defaultValue, p.description.c_str());
        }
    }
    return 0;
}

}  // namespace voxlab::cli
