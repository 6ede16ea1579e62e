// voxlab mesh: an isosurface as a triangle mesh file, extracted by this stage.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "voxlab/error.h"
#include "voxlab/marching_cubes.h"
#include "voxlab/volume.h"

namespace voxlab::cli {
namespace {

int meshCommand(int argc, char** argv) {
    const std::vector<OptionSpec> specs = {
        {"isovalue", "V", "the surface's value, in data units (default: the middle of the value range)"},
        {"out", "FILE", "where to write the mesh: .ply (binary) or .obj (text)"},
        volumeCapOption(),
        {"help", "", "show this help"}};
    const Args args(specs, argc, argv, 2, "mesh");
    if (auto status = usageExit(args, args.positionals().size() != 1,
                                "usage: voxlab mesh DATASET [--isovalue V] [--out FILE.ply|FILE.obj]\n\n"
                                "Extracts the isosurface at V by marching cubes (the stage's C++ functions) and prints its\n"
                                "vertices, triangles, area, enclosed volume and whether it is closed; with --out, writes it\n"
                                "for MeshLab, ParaView or Blender. Coordinates are world units (voxel centre (i,j,k) at\n"
                                "(i+1/2, j+1/2, k+1/2) * spacing); triangles face the lower values.\n\n",
                                specs))
        return *status;
    const Volume volume = loadDatasetArgument(args);
    const double isovalue = args.get("isovalue") ? parseNumber(*args.get("isovalue"), "--isovalue")
                                                 : 0.5 * (volume.minValue() + volume.maxValue());
    const auto start = std::chrono::steady_clock::now();
    const TriangleMesh mesh = extractIsosurface(volume, isovalue);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const MeshMeasures m = measureMesh(mesh);
    std::printf("%s at %g: %zu vertices, %zu triangles in %.2f s\n", volume.name().c_str(), isovalue,
                mesh.vertices.size(), mesh.triangles.size(), seconds);
    std::printf("area %.6g, enclosed volume %.6g (world units), %s\n", m.area, m.volume,
                m.watertight() ? "closed (every edge shared by two triangles)"
                               : ("open: " + std::to_string(m.boundaryEdges) + " boundary edges, " +
                                  std::to_string(m.nonManifoldEdges) + " edges with more than two triangles")
                                     .c_str());
    if (auto out = args.get("out")) {
        saveMesh(mesh, *out);
        std::printf("%s\n", out->c_str());
    }
    return 0;
}

}  // namespace
}  // namespace voxlab::cli

VOXLAB_COMMANDS(marching_cubes) {
    commands.push_back({"mesh", "DATASET", "an isosurface as a triangle mesh (marching cubes), .ply or .obj", &meshCommand});
}
