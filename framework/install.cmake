# `cmake --install` and the release package (CPack, a Debian .deb).
#
#   bin/voxlab, bin/voxlab-stage-host        the programs (the host beside voxlab)
#   share/voxlab/shaders, datasets, ...      the project root voxlab finds from
#                                            its own location (voxlab/project_root.h)
#   share/voxlab/framework/include           the headers C++ stages compile against,
#                                            one folder per module (MODULE/voxlab/*.h)
#   share/voxlab/framework/stages            the stages' own shaders and C++ contracts
#                                            (STAGE/include/voxlab/*.h)
#   share/voxlab/framework/stage_library     the exports every stage library links,
#                                            prebuilt, and the precompiled prelude
#   share/doc/voxlab                         the documentation
#
# An installed voxlab needs neither this checkout nor $VOXLAB_ROOT: it renders,
# views and grades (C++ stages included) from any folder.
include(GNUInstallDirs)
set(VOXLAB_INSTALL_ROOT ${CMAKE_INSTALL_DATADIR}/voxlab)

install(TARGETS voxlab voxlab-stage-host RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# What the project root holds, as far as this tree has it (a student
# release has no reference/, and only the golden scenes of tests/).
install(DIRECTORY shaders datasets assignments DESTINATION ${VOXLAB_INSTALL_ROOT})
foreach(folder reference courses expected)
  if(EXISTS "${PROJECT_SOURCE_DIR}/${folder}")
    install(DIRECTORY ${folder} DESTINATION ${VOXLAB_INSTALL_ROOT})
  endif()
endforeach()
if(EXISTS "${PROJECT_SOURCE_DIR}/tests/golden/scenes")
  install(DIRECTORY tests/golden/scenes DESTINATION ${VOXLAB_INSTALL_ROOT}/tests/golden)
endif()

install(DIRECTORY framework/include DESTINATION ${VOXLAB_INSTALL_ROOT}/framework)
# The stages' own shaders (entry, probe, precomputation passes) and the
# contracts of the C++ stages, with the list generated from them
# (voxlab/stage_contracts.h, which stage_exports.cpp reads).
install(DIRECTORY framework/stages DESTINATION ${VOXLAB_INSTALL_ROOT}/framework
        FILES_MATCHING PATTERN "*.frag" PATTERN "*.vert" PATTERN "*.glsl" REGEX "/include/voxlab/[^/]*[.]h$")
install(FILES ${PROJECT_BINARY_DIR}/framework/generated/voxlab/stage_contracts.h
        DESTINATION ${VOXLAB_INSTALL_ROOT}/framework/include/mesh/voxlab)
install(FILES framework/stage_library/stage_exports.cpp framework/stage_library/stage_prelude.h
        DESTINATION ${VOXLAB_INSTALL_ROOT}/framework/stage_library)
install(FILES $<TARGET_OBJECTS:voxlab_stage_exports>
        DESTINATION ${VOXLAB_INSTALL_ROOT}/framework/stage_library RENAME stage_exports.o)
set(VOXLAB_STAGE_PRELUDE ${PROJECT_BINARY_DIR}/framework/stage_prelude/voxlab_stage_prelude.h)
install(FILES ${VOXLAB_STAGE_PRELUDE} ${VOXLAB_STAGE_PRELUDE}.gch
        DESTINATION ${VOXLAB_INSTALL_ROOT}/framework/stage_library/prelude)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The .deb (cpack -G DEB in the build folder): Debian's conventions, its
# libraries found by dpkg-shlibdeps, and what grading C++ stages needs at
# run time (the compiler and the headers the stage headers include).
set(CPACK_PACKAGE_NAME voxlab)
set(CPACK_PACKAGE_VENDOR "voxlab")
set(CPACK_PACKAGE_CONTACT "voxlab maintainers <voxlab@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "teaching framework for volume rendering with graded plug-in assignments")
set(CPACK_PACKAGE_DESCRIPTION "voxlab renders volumes with OpenGL 3.3 core (a window, or headless through OSMesa or EGL), and grades students' renderer stages against a reference: images and function checks, in a sandbox.")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION education)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "g++, libglm-dev, nlohmann-json3-dev")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "xvfb")
include(CPack)
