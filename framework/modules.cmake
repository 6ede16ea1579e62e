# The framework's modules, lowest first, and the modules each one uses.
#
# A module is a folder, framework/src/<module>/ (the stages: the stage
# folders, framework/stages/), built as the static library voxlab_<module>
# that links, PUBLIC, the modules named after DEPENDS: what it may include
# and call, with theirs in turn. Nothing else is allowed, and two checks
# hold each module to it (CTest `module_layers`, tools/check_modules.py,
# which reads this file):
#   - its files include headers of these modules only;
#   - its compiled objects (`--objects BUILD_DIR`) use symbols of these
#     modules only (what a static library's link order would otherwise
#     hide until some program happened to need the wrong one first).
# A lower module never reaches a higher one. Where a lower one needs what
# is defined above it (the engine its renderers), it is handed it (the
# RenderEngine is constructed with a RendererRegistry).
#
# voxlab_module(<module> [DEPENDS <module>...]) declares one; the library
# itself is made by voxlab_add_module (framework/CMakeLists.txt). A module
# without sources ("contracts", the stages' C++ contracts) is an INTERFACE
# library: headers only.
voxlab_module(io)                                # errors, files, numbers, the project root
voxlab_module(image DEPENDS io)                  # images, PNG, metrics
voxlab_module(volume DEPENDS io)                 # volumes, loaders, phantoms, the camera
voxlab_module(gl DEPENDS io)                     # contexts, shaders, the stubs in a stage's text
voxlab_module(scene DEPENDS volume image)        # scenes, transfer functions, labels
voxlab_module(contracts DEPENDS scene)           # the C++ stages' contracts (framework/stages/*/include/)
voxlab_module(mesh DEPENDS contracts)            # the C++ stage table, stage libraries, the linked-in stages
voxlab_module(render DEPENDS gl mesh)            # the engine
voxlab_module(renderers DEPENDS render)          # what several stages' renderers share
voxlab_module(checks DEPENDS gl scene)           # what the stages' function checks share, GLSL probes
voxlab_module(stages DEPENDS renderers checks)   # the stage folders, and their registry
voxlab_module(report DEPENDS image)              # HTML reports, and students' text kept as data
voxlab_module(sandbox DEPENDS mesh)              # child processes under default deny, the stage host
voxlab_module(grade DEPENDS stages sandbox report)  # the grader: jobs, the checks' list, scores
voxlab_module(window DEPENDS stages)             # the viewer
voxlab_module(cli DEPENDS window grade)          # the `voxlab` program (framework/cli/)
