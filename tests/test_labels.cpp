// Label maps (the labels stage with composite) against CPU compositing
// written here from the handout's definitions (support/cpu_ray.h):
//  - nearest: a sample's label is that of the voxel whose cell contains it
//    (floor of the voxel coordinate, clamped to the grid);
//  - masks: the 8 voxels around the sample, each with its trilinear weight,
//    classify the sample's value with their own labels, premultiplied; the
//    colour is the blend divided by its opacity;
//  - each label is classified by its class's function, the scene's function
//    when it has no class (label 0 too), or not at all when hidden; the value
//    is always the trilinearly interpolated data value (cpu_sampling.h).
// Phantoms: the nested labelled spheres (phantoms.h) in the signed CT
// phantom, and random blob labels with anisotropic spacing and classes out
// of label order, from axis views and orbits.
//
// Tolerance: 2 grey levels per channel. The GPU reads every transfer
// function from tables baked to within 0.5/255 (colour and opacity each) and
// composites in float; the 8-bit image rounds once more. Pixels where a
// nearest sample lies within 1e-3 voxel of a border between two labels are
// left out (float and double may pick different sides); the tests count
// them and require them to be few.
//
// The distance field is held to brute force, and bad label maps to one-line
// errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <random>

#include <nlohmann/json.hpp>

#include "support/cpu_ray.h"
#include "support/cpu_sampling.h"
#include "support/gl_fixture.h"
#include "voxlab/error.h"
#include "voxlab/label_map.h"
#include "voxlab/phantoms.h"

namespace voxlab::testing {
namespace {

namespace fs = std::filesystem;

template <class F>
Volume floatVolume(glm::ivec3 d, glm::dvec3 spacing, F f, const std::string& name = "test") {
    std::vector<float> values;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < d.y; ++j)
            for (int i = 0; i < d.x; ++i) values.push_back(float(f(i, j, k)));
    std::vector<std::uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return Volume(d, VoxelType::Float32, spacing, bytes, name);
}

std::string tempPath(const std::string& name) {
    const fs::path dir = fs::path(::testing::TempDir()) / ("voxlab_labels_" + std::to_string(getpid()));
    fs::create_directories(dir);
    return (dir / name).string();
}

// How the test expects each label to be shown.
struct Classes {
    std::vector<ControlPoint> sceneFunction;
    std::map<int, std::optional<std::vector<ControlPoint>>> byLabel;  // nullopt: hidden

    glm::dvec4 classify(int label, double value) const {
        const auto it = byLabel.find(label);
        if (it == byLabel.end()) return cpuTransferFunction(sceneFunction, value);
        if (!it->second) return glm::dvec4(0.0);
        return cpuTransferFunction(*it->second, value);
    }
    // The scene's "labels" for these classes, in the order given.
    LabelMap labelMap(const std::string& volume, LabelSampling sampling, const std::vector<int>& order) const {
        LabelMap m{volume, sampling, {}, std::nullopt};
        for (int label : order) {
            const auto& f = byLabel.at(label);
            m.classes.push_back({label, "", f ? std::optional<TransferFunction>(TransferFunction(*f)) : std::nullopt,
                                 bool(f)});
        }
        return m;
    }
};

// The CPU's classification of a sample at p (see the top of the file).
class CpuLabels {
public:
    CpuLabels(const Volume& data, const Volume& labels, const Classes& classes, LabelSampling sampling)
        : data_(data), labels_(labels), classes_(classes), sampling_(sampling) {}

    int label(glm::ivec3 ijk) const {
        ijk = glm::clamp(ijk, glm::ivec3(0), labels_.dims() - 1);
        return int(labels_.value(ijk.x, ijk.y, ijk.z));
    }
    glm::dvec4 operator()(glm::dvec3 p) const {
        const double value = cpuTrilinear(data_, p);
        const glm::dvec3 u = p / data_.spacing();
        if (sampling_ == LabelSampling::Nearest) {
            const glm::ivec3 cell(glm::floor(u));
            for (int a = 0; a < 3; ++a) {
                const double f = u[a] - std::floor(u[a]);
                glm::ivec3 other = cell;
                other[a] += f < 0.5 ? -1 : 1;
                if (std::min(f, 1.0 - f) < 1e-3 && label(other) != label(cell)) ambiguous_ = true;
            }
            return classes_.classify(label(cell), value);
        }
        const glm::dvec3 shifted = u - 0.5, lower = glm::floor(shifted), w = shifted - lower;
        glm::dvec4 sum(0.0);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            const double weight = (o.x ? w.x : 1 - w.x) * (o.y ? w.y : 1 - w.y) * (o.z ? w.z : 1 - w.z);
            const glm::dvec4 c = classes_.classify(label(glm::ivec3(lower) + o), value);
            sum += weight * glm::dvec4(glm::dvec3(c) * c.a, c.a);
        }
        return sum.a > 0.0 ? glm::dvec4(glm::dvec3(sum) / sum.a, sum.a) : glm::dvec4(0.0);
    }
    mutable bool ambiguous_ = false;

private:
    const Volume& data_;
    const Volume& labels_;
    const Classes& classes_;
    LabelSampling sampling_;
};

struct Agreement {
    double worst = 0.0;
    int compared = 0, ambiguous = 0, visible = 0;
};

// Renders the scene and composites every pixel on the CPU.
Agreement compareWithCpu(RenderEngine& engine, const Volume& data, const Volume& labels, const Classes& classes,
                         const Scene& scene) {
    engine.setVolume(data);
    const Image image = engine.render(scene);
    const Camera cam = Camera::make(scene.camera, data.extent(), scene.width, scene.height);
    const double step = scene.step * data.minSpacing();
    Agreement a;
    for (int y = 0; y < scene.height; ++y)
        for (int x = 0; x < scene.width; ++x) {
            CpuLabels cpu(data, labels, classes, scene.labels->sampling);
            glm::dvec3 o, d;
            cam.ray(x + 0.5, y + 0.5, &o, &d);
            const glm::dvec4 expected = cpuCompositeRay(o, d, data.extent(), {}, step, scene.step, 1.0, cpu);
            if (cpu.ambiguous_) {
                ++a.ambiguous;
                continue;
            }
            ++a.compared;
            a.visible += expected.a > 0.05;
            for (int ch = 0; ch < 3; ++ch)
                a.worst = std::max(a.worst, 255.0 * std::abs(double(image.at(x, y)[ch]) - expected[ch]));
        }
    return a;
}

Scene labelScene(const LabelMap& map, const CameraSpec& camera, int size, const Classes* classes = nullptr) {
    Scene s;
    if (classes) s.transferFunction = TransferFunction(classes->sceneFunction);
    s.renderer = "composite";
    s.camera = camera;
    s.width = s.height = size;
    s.step = 0.5;
    s.interpolation = Interpolation::Trilinear;
    s.parameters = {{"early_termination", 1.0}};
    s.labels = map;
    return s;
}

std::vector<CameraSpec> cameras() {
    std::vector<CameraSpec> out;
    for (const char* view : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
        CameraSpec c;
        c.view = view;
        c.projection = Projection::Orthographic;
        out.push_back(c);
    }
    CameraSpec orbit;  // perspective, oblique
    orbit.azimuth = 33.0, orbit.elevation = 21.0;
    out.push_back(orbit);
    return out;
}

class Labels : public GlTest {};

// The nested spheres: label 2 (offset inner sphere) red to yellow over the
// CT numbers, label 1 green and translucent, label 0 hidden; the classes
// listed 2, 0, 1 so that rows are not labels.
Classes nestedClasses() {
    Classes c;
    c.sceneFunction = {{-1000, glm::vec3(0.3f, 0.4f, 1.0f), 0.0f}, {0, glm::vec3(0.3f, 0.4f, 1.0f), 0.05f}};
    c.byLabel[2] = std::vector<ControlPoint>{{-200, glm::vec3(1.0f, 0.3f, 0.1f), 0.1f},
                                             {700, glm::vec3(1.0f, 0.9f, 0.2f), 0.4f}};
    c.byLabel[1] = std::vector<ControlPoint>{{-800, glm::vec3(0.1f, 0.8f, 0.3f), 0.15f},
                                             {700, glm::vec3(0.8f, 0.8f, 0.8f), 0.02f}};
    c.byLabel[0] = std::nullopt;
    return c;
}

TEST_F(Labels, NestedSpheresMatchCpuCompositingFromEveryAxisAndAnOrbit) {
    const Volume data = loadVolume("phantom:ct-signed:40");
    const Volume labels = loadVolume("phantom:nested-labels:40");
    const Classes classes = nestedClasses();
    for (LabelSampling sampling : {LabelSampling::Nearest, LabelSampling::Masks})
        for (const CameraSpec& cam : cameras()) {
            const Scene scene =
                labelScene(classes.labelMap("phantom:nested-labels:40", sampling, {2, 0, 1}), cam, 48, &classes);
            const Agreement a = compareWithCpu(engine(), data, labels, classes, scene);
            const std::string what = std::string(sampling == LabelSampling::Masks ? "masks" : "nearest") + " " +
                                     (cam.view.empty() ? "orbit" : cam.view);
            std::printf("nested %-12s worst %.2f levels over %d pixels (%d visible, %d ambiguous)\n", what.c_str(),
                        a.worst, a.compared, a.visible, a.ambiguous);
            EXPECT_LE(a.worst, 2.0) << what;
            EXPECT_GT(a.visible, 300) << what;
            EXPECT_LT(a.ambiguous, a.compared / 50) << what;
        }
}

// Random blobs of labels 0..4 on an anisotropic grid: label 3 hidden, label
// 4 without a class (the scene's function), the classes listed 3, 2, 1.
TEST_F(Labels, RandomLabelsOnAnAnisotropicGridMatchCpuCompositing) {
    const glm::ivec3 dims(18, 14, 11);
    const glm::dvec3 spacing(1.5, 1.0, 2.5);
    std::mt19937 rng(20261126);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<glm::dvec3> seeds(12);
    for (glm::dvec3& s : seeds) s = glm::dvec3(uni(rng), uni(rng), uni(rng)) * glm::dvec3(dims);
    const Volume labels = floatVolume(dims, spacing, [&](int i, int j, int k) {
        const glm::dvec3 p(i + 0.5, j + 0.5, k + 0.5);
        std::size_t nearest = 0;
        for (std::size_t s = 1; s < seeds.size(); ++s)
            if (glm::length(p - seeds[s]) < glm::length(p - seeds[nearest])) nearest = s;
        return double(nearest % 5);
    });
    const Volume data = floatVolume(dims, spacing, [&](int, int, int) { return -50.0 + 100.0 * uni(rng); });
    const std::string labelFile = tempPath("blobs.nrrd");
    saveNrrd(labels, labelFile);

    Classes classes;
    classes.sceneFunction = {{-50, glm::vec3(0.9f, 0.9f, 0.9f), 0.02f}, {50, glm::vec3(0.2f, 0.2f, 0.9f), 0.2f}};
    classes.byLabel[3] = std::nullopt;
    classes.byLabel[2] = std::vector<ControlPoint>{{-50, glm::vec3(1.0f, 0.2f, 0.2f), 0.4f},
                                                   {50, glm::vec3(1.0f, 0.8f, 0.2f), 0.05f}};
    classes.byLabel[1] = std::vector<ControlPoint>{{0, glm::vec3(0.2f, 1.0f, 0.4f), 0.3f}};
    for (LabelSampling sampling : {LabelSampling::Nearest, LabelSampling::Masks})
        for (const CameraSpec& cam : cameras()) {
            const Scene scene = labelScene(classes.labelMap(labelFile, sampling, {3, 2, 1}), cam, 40, &classes);
            const Agreement a = compareWithCpu(engine(), data, labels, classes, scene);
            const std::string what = std::string(sampling == LabelSampling::Masks ? "masks" : "nearest") + " " +
                                     (cam.view.empty() ? "orbit" : cam.view);
            std::printf("blobs  %-12s worst %.2f levels over %d pixels (%d visible, %d ambiguous)\n", what.c_str(),
                        a.worst, a.compared, a.visible, a.ambiguous);
            EXPECT_LE(a.worst, 2.0) << what;
            EXPECT_GT(a.visible, 300) << what;
            EXPECT_LT(a.ambiguous, a.compared / 20) << what;
        }
}

// A hidden label and a label map that only repeats the scene's function
// change nothing but what they should: the oracle's own sanity.
TEST_F(Labels, WithoutClassesALabelMapChangesNothing) {
    const Volume data = loadVolume("phantom:ct-signed:32");
    Scene plain = labelScene(LabelMap{"phantom:nested-labels:32", LabelSampling::Nearest, {}, std::nullopt},
                             cameras().back(), 40);
    plain.transferFunction = TransferFunction({{-900, glm::vec3(1.0f), 0.0f}, {700, glm::vec3(1.0f, 0.5f, 0.2f), 0.3f}});
    engine().setVolume(data);
    const Image labelled = engine().render(plain);
    plain.labels.reset();
    const Image unlabelled = engine().render(plain);
    double worst = 0.0;
    for (std::size_t i = 0; i < labelled.rgba.size(); ++i)
        worst = std::max(worst, 255.0 * std::abs(double(labelled.rgba[i]) - double(unlabelled.rgba[i])));
    EXPECT_LE(worst, 1.0) << "label 0, 1 and 2 without classes all use the scene's function";
}

// The distance transform against brute force on a small anisotropic grid.
TEST(LabelDistance, EqualsTheBruteForceDistanceToTheNearestLabelledVoxel) {
    const glm::ivec3 dims(9, 7, 6);
    const glm::dvec3 spacing(1.3, 0.7, 2.1);
    std::mt19937 rng(7);
    std::vector<std::uint16_t> labels(std::size_t(dims.x) * dims.y * dims.z);
    for (auto& l : labels) l = std::uint16_t(rng() % 9 == 0 ? 4 : rng() % 3);
    const std::vector<float> d = distanceToLabel(labels, dims, spacing, 4);
    double worst = 0.0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                double best = 1e300;
                for (int c = 0; c < dims.z; ++c)
                    for (int b = 0; b < dims.y; ++b)
                        for (int a = 0; a < dims.x; ++a)
                            if (labels[std::size_t(a + dims.x * (b + dims.y * c))] == 4)
                                best = std::min(best, glm::length(glm::dvec3(i - a, j - b, k - c) * spacing));
                worst = std::max(worst, std::abs(best - d[std::size_t(i + dims.x * (j + dims.y * k))]));
            }
    EXPECT_LT(worst, 1e-5);
    EXPECT_THROW(distanceToLabel(labels, dims, spacing, 7), Error);
}

// The distance-based function recolours what it applies to: a colour by
// distance to label 2 on label 1's voxels, compared on the CPU.
TEST_F(Labels, TheDistanceFunctionRecoloursByTheDistanceToTheChosenLabel) {
    const Volume data = loadVolume("phantom:ct-signed:32");
    const Volume labels = loadVolume("phantom:nested-labels:32");
    const std::vector<std::uint16_t> values = checkedLabels(labels, data);
    const std::vector<float> field = distanceToLabel(values, data.dims(), data.spacing(), 2);
    Classes classes = nestedClasses();
    const std::vector<ControlPoint> byDistance = {{0.0, glm::vec3(1.0f, 1.0f, 0.0f), 1.0f},
                                                  {8.0, glm::vec3(0.0f, 0.3f, 1.0f), 0.2f}};
    Scene scene = labelScene(classes.labelMap("phantom:nested-labels:32", LabelSampling::Nearest, {2, 0, 1}),
                             cameras()[4], 32);
    scene.labels->distance = LabelDistance{2, TransferFunction(byDistance), {1}};
    engine().setVolume(data);
    const Image image = engine().render(scene);
    // The distance at a sample: the field interpolated trilinearly, as a texture.
    const Volume distance = floatVolume(data.dims(), data.spacing(), [&](int i, int j, int k) {
        return double(field[std::size_t(i + 32 * (j + 32 * k))]);
    });
    const Camera cam = Camera::make(scene.camera, data.extent(), scene.width, scene.height);
    double worst = 0.0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            CpuLabels cpu(data, labels, classes, LabelSampling::Nearest);
            const auto recoloured = [&](glm::dvec3 p) {
                const glm::dvec4 c = cpu(p);
                if (cpu.label(glm::ivec3(glm::floor(p))) != 1 || c.a <= 0.0) return c;
                const glm::dvec4 f = cpuTransferFunction(byDistance, cpuTrilinear(distance, p));
                return glm::dvec4(glm::dvec3(f), c.a * f.a);
            };
            glm::dvec3 o, d;
            cam.ray(x + 0.5, y + 0.5, &o, &d);
            const glm::dvec4 expected = cpuCompositeRay(o, d, data.extent(), {}, 0.5, 0.5, 1.0, recoloured);
            for (int ch = 0; ch < 3; ++ch)
                worst = std::max(worst, 255.0 * std::abs(double(image.at(x, y)[ch]) - expected[ch]));
        }
    std::printf("distance-coloured nested spheres: worst %.2f levels\n", worst);
    EXPECT_LE(worst, 2.0);
}

TEST_F(Labels, BadLabelMapsAreOneLineErrors) {
    const Volume data = loadVolume("phantom:ct-signed:32");
    engine().setVolume(data);
    const auto message = [&](Scene scene) {
        try {
            engine().render(scene);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    const CameraSpec cam = cameras().back();
    const std::string grid = message(labelScene({"phantom:nested-labels:16", {}, {}, std::nullopt}, cam, 8));
    EXPECT_NE(grid.find("the label map is 16x16x16 but the volume is 32x32x32"), std::string::npos) << grid;
    const std::string fraction = message(labelScene({"phantom:ramp-x:32", {}, {}, std::nullopt}, cam, 8));
    EXPECT_NE(fraction.find("whole numbers 0..65535, not 0.5"), std::string::npos) << fraction;
    const std::string negative = message(labelScene({"phantom:ct-signed:32", {}, {}, std::nullopt}, cam, 8));
    EXPECT_NE(negative.find("not -1000"), std::string::npos) << negative;
    const std::string missing = message(labelScene({"/nonexistent/labels.nrrd", {}, {}, std::nullopt}, cam, 8));
    EXPECT_NE(missing.find("labels.nrrd"), std::string::npos) << missing;
    Scene mip = labelScene({"phantom:nested-labels:32", {}, {}, std::nullopt}, cam, 8);
    mip.renderer = "mip";
    mip.parameters.clear();
    EXPECT_NE(message(mip).find("mip: does not draw label maps"), std::string::npos) << message(mip);
    Scene preintegrated = labelScene({"phantom:nested-labels:32", {}, {}, std::nullopt}, cam, 8);
    preintegrated.parameters["preintegrated"] = 1;
    EXPECT_NE(message(preintegrated).find("'preintegrated' does not combine with a label map"), std::string::npos);
    Scene far = labelScene({"phantom:nested-labels:32", {}, {}, std::nullopt}, cam, 8);
    far.labels->distance = LabelDistance{9, TransferFunction({{0, glm::vec3(1.0f), 1.0f}}), {}};
    EXPECT_NE(message(far).find("no voxel carries label 9"), std::string::npos);
    for (const std::string& m : {grid, fraction, negative, missing}) EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    // The engine still renders after every refusal.
    EXPECT_NO_THROW(engine().render(labelScene({"phantom:nested-labels:32", {}, {}, std::nullopt}, cam, 8)));
}

TEST(LabelScenes, KeysAreCheckedAndRoundTrip) {
    const auto parse = [](const std::string& text) {
        return Scene::fromJson(nlohmann::json::parse(text), "s.json", "");
    };
    const Scene s = parse(R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels",
        "sampling": "masks", "classes": [{"label": 2, "name": "inner", "visible": false},
        {"label": 1, "transfer_function": [{"value": 0, "color": [1,0,0], "alpha": 0.5}]}],
        "distance": {"to": 2, "transfer_function": [{"value": 0, "color": [1,1,0], "alpha": 1}], "apply_to": [1]}}})");
    ASSERT_TRUE(s.labels);
    EXPECT_EQ(s.labels->sampling, LabelSampling::Masks);
    ASSERT_EQ(s.labels->classes.size(), 2u);
    EXPECT_FALSE(s.labels->classes[0].visible);
    EXPECT_EQ(s.labels->find(1)->transferFunction->points().size(), 1u);
    const Scene again = Scene::fromJson(s.toJson(), "again", "");
    EXPECT_EQ(again.toJson(), s.toJson());
    const std::vector<std::pair<std::string, std::string>> bad = {
        {R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels", "colour": 1}})", "labels.colour: unknown key"},
        {R"({"dataset": "phantom:sphere", "labels": {"classes": []}})", "labels.volume: missing"},
        {R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels", "classes": [{"name": "x"}]}})", "labels.classes[0].label: missing"},
        {R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels", "classes": [{"label": 1.5}]}})", "labels.classes[0].label: expected a label"},
        {R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels", "classes": [{"label": 1}, {"label": 1}]}})", "label 1 has a class already"},
        {R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels", "sampling": "linear"}})", "unknown sampling 'linear'"},
        {R"({"dataset": "phantom:sphere", "labels": {"volume": "phantom:nested-labels", "distance": {"to": 1}}})", "labels.distance.transfer_function: missing"},
    };
    for (const auto& [text, expected] : bad) {
        try {
            parse(text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace voxlab::testing
