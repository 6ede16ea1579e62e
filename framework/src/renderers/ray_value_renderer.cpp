// voxlab renderer for ray-value stages (see renderers.h): what differs
// between MinIP, the average and the like is the stage's name, its
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

RayValueRenderer::RayValueRenderer(std::string stage, std::string description, ProfileModel profile,
                                   std::vector<ParameterSpec> parameters)
    : stage_(std::move(stage)), description_(std::move(description)), profile_(profile),
      parameters_(std::move(parameters)) {}

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
    for (std::size_t at = shader.find("STAGE_NAME"); at != std::string::npos; at = shader.find("STAGE_NAME", at))
        shader.replace(at, 10, stage_);
    return {{fragmentShader(), shader}};
}

}  // namespace voxlab
