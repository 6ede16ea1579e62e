// Every shader is written once, in GLSL 330 core, and the browser build
// compiles it as GLSL ES 3.00 (WebGL 2; voxlab/shader.h: GlslDialect). These
// tests hold every program the framework builds to both dialects, with an
// independent compiler: Khronos's reference front end, glslangValidator
// (Debian's glslang-tools), which checks a shader against the specification
// of the version it declares, stricter than any one driver. Mesa accepting
// a shader says little about ANGLE in a browser; the specification does.
//
// What is validated: each renderer's vertex and fragment shader (generated
// ones included) with the reference's stages and with the starter's, and
// every other entry shader under shaders/ (probes, precomputation, the
// viewer's). The control test shows the validator bites: an implicit int to
// float conversion is valid 330 core and invalid ES 3.00, and the ES text
// of a shader that has one must be refused.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>

#include "voxlab/project_root.h"
#include "voxlab/renderer.h"
#include "voxlab/scene.h"
#include "voxlab/shader.h"
#include "voxlab/stage_registry.h"

namespace voxlab {
namespace {

namespace fs = std::filesystem;

std::string validator() {
    for (const char* dir : {"/usr/bin", "/usr/local/bin"}) {
        const std::string path = std::string(dir) + "/glslangValidator";
        if (fs::exists(path)) return path;
    }
    return "";
}

// glslangValidator's verdict on `text` as a shader of `stage` ("vert" or
// "frag"): "" when valid, else its log (the first lines).
std::string validate(const std::string& text, const std::string& stage) {
    static int counter = 0;
    const fs::path dir = fs::temp_directory_path() / ("voxlab_glsl_es_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path file = dir / ("s" + std::to_string(counter++) + "." + stage);
    std::ofstream(file) << text;
    const std::string command = validator() + " " + file.string() + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string log;
    char buf[512];
    while (pipe && std::fgets(buf, sizeof buf, pipe)) log += buf;
    const int status = pipe ? ::pclose(pipe) : -1;
    fs::remove(file);
    if (status == 0) return "";
    return log.substr(0, 1200);
}

struct Failure {
    std::string what;
    std::string log;
};

void validateProgram(ShaderLibrary& library, const std::string& vertex, const std::string& fragment,
                     const std::string& label, std::vector<Failure>& failures, int* count) {
    for (const auto& [name, stage] : {std::pair{vertex, "vert"}, std::pair{fragment, "frag"}}) {
        if (name.empty()) continue;
        for (GlslDialect dialect : {GlslDialect::Core330, GlslDialect::Es300}) {
            library.setDialect(dialect);
            const std::string where = label + " " + name + (dialect == GlslDialect::Es300 ? " (ES 3.00)" : " (330 core)");
            try {
                const PreprocessedShader shader = library.preprocess(name);
                const std::string log = validate(shader.text, stage);
                if (!log.empty()) failures.push_back({where, shader.mapLog(log)});
            } catch (const std::exception& e) {
                failures.push_back({where, e.what()});
            }
            ++*count;
        }
    }
}

std::string report(const std::vector<Failure>& failures) {
    std::ostringstream out;
    for (const Failure& f : failures) out << f.what << ":\n" << f.log << "\n";
    return out.str();
}

class GlslEs : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_FALSE(validator().empty())
            << "glslangValidator is missing: apt-get install glslang-tools (tools/setup.sh --test installs it)";
    }
};

TEST_F(GlslEs, TheValidatorRefusesAnImplicitConversionInEsButNotInCore) {
    const std::string body = "\nout vec4 colour;\nvoid main() { float x = 1; colour = vec4(x); }\n";
    EXPECT_EQ(validate(versionPreamble("#version 330 core", GlslDialect::Core330, "t") + body, "frag"), "");
    EXPECT_NE(validate(versionPreamble("#version 330 core", GlslDialect::Es300, "t") + body, "frag"), "");
    // And the ES preamble itself is what makes a sampler3D declarable.
    const std::string sampler = "\nuniform sampler3D v;\nout vec4 c;\nvoid main() { c = texture(v, vec3(0.5)); }\n";
    EXPECT_EQ(validate(versionPreamble("#version 330 core", GlslDialect::Es300, "t") + sampler, "frag"), "");
    EXPECT_NE(validate("#version 300 es\nprecision highp float;" + sampler, "frag"), "");
}

TEST_F(GlslEs, AnEntryShaderMustStartWithTheCoreVersionLine) {
    EXPECT_THROW(versionPreamble("#version 450", GlslDialect::Es300, "x.frag:1"), ShaderError);
    EXPECT_THROW(versionPreamble("void main() {}", GlslDialect::Core330, "x.frag:1"), ShaderError);
    EXPECT_NO_THROW(versionPreamble("#version 330 core  // comment", GlslDialect::Es300, "x.frag:1"));
}

// Each renderer's program with the reference's stages and with the
// starter's (whose stubs must compile too: a student starts from them).
TEST_F(GlslEs, EveryRendererProgramIsValidInBothDialects) {
    std::vector<Failure> failures;
    int count = 0;
    for (const std::string tree : {"reference", "assignments"}) {
        ShaderLibrary library = ShaderLibrary::forImplementation(projectRoot() + "/" + tree);
        for (const auto& renderer : rendererRegistry().all()) {
            for (const auto& [name, text] : renderer->generatedShaders()) library.addGenerated(name, text);
            validateProgram(library, renderer->vertexShader(), renderer->fragmentShader(), tree + ": " + renderer->id(),
                            failures, &count);
        }
    }
    EXPECT_TRUE(failures.empty()) << failures.size() << " of " << count << " shaders invalid:\n" << report(failures);
    EXPECT_GT(count, 4 * int(rendererRegistry().all().size()));
}

// The other entry shaders: function-check probes, precomputation passes,
// the viewer's, the engine's own passes (bricks, resolve, counting).
TEST_F(GlslEs, EveryOtherEntryShaderIsValidInBothDialects) {
    std::vector<Failure> failures;
    int count = 0;
    ShaderLibrary library = ShaderLibrary::forImplementation(projectRoot() + "/reference");
    std::set<std::string> renderers;  // above, with their generated parts
    for (const auto& renderer : rendererRegistry().all())
        renderers.insert({renderer->fragmentShader(), renderer->vertexShader()});
    for (const fs::path folder : frameworkShaderFolders()) {
        const bool stages = folder == fs::path(stagesRoot());
        for (const auto& entry : fs::recursive_directory_iterator(folder)) {
            const std::string ext = entry.path().extension().string();
            if (ext != ".frag" && ext != ".vert") continue;
            const std::string name = (stages ? "stages/" : "") + fs::relative(entry.path(), folder).string();
            if (renderers.count(name)) continue;
            validateProgram(library, ext == ".vert" ? name : "", ext == ".frag" ? name : "", folder.filename().string() + "/",
                            failures, &count);
        }
    }
    EXPECT_TRUE(failures.empty()) << failures.size() << " of " << count << " shaders invalid:\n" << report(failures);
    EXPECT_GT(count, 20);
}

}  // namespace
}  // namespace voxlab
