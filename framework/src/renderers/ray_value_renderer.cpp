// voxlab renderer for ray-value stages (see renderers.h): what differs
// between MinIP, the mean and the like is the stage's name, its
// description and parameters, so the framework holds one class and one
// shader template for all of them. The declaration is the registry's line,
// not a file read at run time: a sandboxed grading worker, which may read
// only its snapshot and shaders/, builds the same registry.
#include <fstream>
#include <sstream>

#include "voxlab/error.h"
#include "voxlab/renderers.h"
#include "voxlab/scene.h"

namespace voxlab {
namespace {

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
}

// How the entry shader calls the stage (voxlab/runs.glsl): a largest or
// smallest value can be taken over runs between bricks that cannot change
// it; any other value needs the whole ray in one call.
std::string runDefines(ProfileModel profile, RayResult result) {
    if (result == RayResult::Colour) return "#define RAY_PIXEL STAGE_NAME_ray";
    const std::string pixel = "\n#define RAY_PIXEL(ray) display_value(RAY_VALUE(ray))";
    if (profile == ProfileModel::Maximum)
        return "#define RUN_LARGEST STAGE_NAME_ray\n#define RAY_VALUE largest_over_runs" + pixel;
    if (profile == ProfileModel::Minimum)
        return "#define RUN_SMALLEST STAGE_NAME_ray\n#define RAY_VALUE smallest_over_runs" + pixel;
    return "#define RAY_VALUE STAGE_NAME_ray" + pixel;
}

}  // namespace

RayValueRenderer::RayValueRenderer(std::string stage, std::string description, ProfileModel profile,
                                   std::vector<ParameterSpec> parameters, RayResult result)
    : stage_(std::move(stage)), description_(std::move(description)), profile_(profile),
      parameters_(std::move(parameters)), result_(result) {}

// A largest or smallest value, or a mean, is the same over the parts of a
// ray as over the whole; a value that depends on the samples in front (the
// attenuated MIP) is not.
BrickCombine RayValueRenderer::brickCombine(const ParameterValues&) const {
    if (result_ == RayResult::Colour) return BrickCombine::None;  // its colour depends on the samples in front
    switch (profile_) {
        case ProfileModel::Maximum: return BrickCombine::Largest;
        case ProfileModel::Minimum: return BrickCombine::Smallest;
        case ProfileModel::Mean: return BrickCombine::Sum;
        default: return BrickCombine::None;
    }
}

std::map<std::string, std::string> RayValueRenderer::generatedShaders() const {
    const std::string templatePath = projectRoot() + "/shaders/renderers/ray_value.frag.in";
    std::ifstream in(templatePath, std::ios::binary);
    if (!in) throw Error(templatePath + ": cannot read the ray-value shader template");
    std::ostringstream text;
    text << in.rdbuf();
    // The template's comment header documents the placeholders: the shader
    // is a header of its own, then the template from its first #include on.
    const std::string body = text.str();
    const std::size_t from = body.find("#include");
    if (from == std::string::npos) throw Error(templatePath + ": no #include in the template");
    std::string shader = "#version 330 core\n// Renderer \"" + stage_ +
                         "\", made from shaders/renderers/ray_value.frag.in: " + stage_ + "_ray() of each pixel's ray.\n" +
                         body.substr(from);
    replaceAll(shader, "RUN_DEFINES", runDefines(profile_, result_));
    replaceAll(shader, "STAGE_NAME", stage_);
    return {{fragmentShader(), shader}};
}

}  // namespace voxlab
