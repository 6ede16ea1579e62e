// voxlab stage shadows: shadows from a light volume as a compositing
// component (voxlab/renderers.h): light_volume.frag fills a 3D texture with
// the stage's light_transmittance() towards the light, which dims each lit
// sample.
#include <cstdio>

#include "voxlab/camera.h"
#include "voxlab/renderers.h"
#include "voxlab/scene.h"
#include "voxlab/volume.h"

namespace voxlab {
namespace {

class ShadowsComponent final : public CompositeComponent {
public:
    Phase phase() const override { return Phase::Lit; }
    std::vector<ParameterSpec> parameters() const override {
        // The light volume is computed again whenever the camera turns (the
        // light turns with it): on the bonsai, 64 per axis costs about 0.1 s
        // a time, 128 about 0.7 s (docs/performance.md).
        return {{"shadows", ParameterType::Bool, 0, 1, 0,
                 "dim each lit sample by the transmittance towards the light (a light volume; turn the light "
                 "away from the view to see them)"},
                {"shadow_resolution", ParameterType::Int, 16, 256, 64,
                 "shadows: the light volume's voxels along each axis, at most (finer shadows, slower to compute)"}};
    }
    // The light volume covers the whole volume.
    bool readsBeyondBrick() const override { return true; }
    // The light volume: the volume's dimensions, at most shadow_resolution
    // voxels on each axis. The light turns with the camera (lighting.glsl):
    // its direction is fixed by the camera's axes and the two light angles.
    std::vector<Precomputation> precomputations(const Scene& scene, const Volume& volume,
                                                const ParameterValues& values) const override {
        const Camera cam = Camera::make(scene.camera, volume.extent(), scene.width, scene.height);
        char key[256];
        std::snprintf(key, sizeof key, "f=%.7g,%.7g,%.7g r=%.7g,%.7g,%.7g d=%.7g,%.7g,%.7g light=%.7g,%.7g",
                      cam.forward.x, cam.forward.y, cam.forward.z, cam.right.x, cam.right.y, cam.right.z, cam.down.x,
                      cam.down.y, cam.down.z, values.at("light_azimuth"), values.at("light_elevation"));
        const glm::ivec3 size = glm::min(volume.dims(), glm::ivec3(int(values.at("shadow_resolution"))));
        return {{"u_light_volume", "stages/shadows/light_volume.frag", size, 1, key}};
    }
};

}  // namespace
}  // namespace voxlab

VOXLAB_COMPOSITE_COMPONENTS(shadows) { components.add<voxlab::ShadowsComponent>(); }
