# The libFuzzer targets, one per parser (tests/fuzz/fuzz_NAME.cpp), and the
# framework sources they compile. Included by tests/fuzz/CMakeLists.txt
# (the clang sub-build) and tests/CMakeLists.txt (their CTest entries).
set(VOXLAB_FUZZ_TARGETS
  nrrd            # NRRD, attached data
  nrrd_detached   # NRRD, detached header + data file
  fld             # AVS field
  dat             # .dat + .raw
  scene           # scene JSON
  tf              # 1D transfer function
  tf2d            # 2D transfer function
  viewer_script   # viewer scripts
  deck            # demo decks
  dicom           # DICOM series of two files (through GDCM)
  report_text)    # students' text through the grader's report writers

# The parsers and what they call, and the grader's report writers; nothing
# that needs OpenGL.
set(VOXLAB_FUZZ_FRAMEWORK_SOURCES
  src/volume/volume.cpp
  src/volume/volume_io_util.cpp
  src/volume/voxel_store.cpp
  src/volume/nrrd_loader.cpp
  src/volume/fld_loader.cpp
  src/volume/dat_raw_loader.cpp
  src/volume/load_volume.cpp
  src/volume/dicom_loader.cpp
  src/volume/dicom_child.cpp
  src/volume/phantoms.cpp
  src/scene/scene.cpp
  src/scene/scene_sections.cpp  # with the stages' section.cpp (tests/fuzz/CMakeLists.txt)
  src/scene/json_text.cpp
  src/scene/data_path.cpp
  src/io/project_root.cpp
  src/scene/transfer_function.cpp
  src/scene/transfer_function_2d.cpp
  src/scene/viewer_script.cpp
  src/scene/deck.cpp
  src/volume/camera.cpp
  src/io/atomic_file.cpp
  src/io/fd_io.cpp
  src/io/number_text.cpp
  # the report writers (fuzz_report_text): pure text, no GL or processes
  src/report/untrusted_text.cpp
  src/report/html_text.cpp
  src/report/html_report.cpp
  src/report/html_report_style.cpp
  src/report/html_class_report.cpp
  src/grade/grade_results.cpp)
