# `vis4gs view`: the Qt5 application of the linked views (issue 10). Included from
# CMakeLists.txt after the vis4gs target exists. Without Qt5 or VTK::GUISupportQt the
# program builds without the `view` command.
find_package(Qt5 QUIET COMPONENTS Widgets)
if (TARGET Qt5::Widgets AND TARGET VTK::GUISupportQt AND TARGET Vis4GS::ViewsLinked)
  set_property(SOURCE Vis4GSMainWindow.h PROPERTY SKIP_AUTOMOC OFF)
  target_sources(vis4gs PRIVATE
    vis4gsViewCommand.cxx
    Vis4GSMainWindow.cxx
    Vis4GSMainWindow.h
    Vis4GSDocument.cxx)
  set_target_properties(vis4gs PROPERTIES AUTOMOC ON)
  target_link_libraries(vis4gs PRIVATE VTK::GUISupportQt Qt5::Widgets
    vis4gs::CoreTrainingLog vis4gs::CoreScene VTK::RenderingCore VTK::RenderingOpenGL2
    VTK::InteractionStyle VTK::RenderingContext2D VTK::ChartsCore VTK::ViewsCore
    VTK::ViewsContext2D VTK::CommonExecutionModel VTK::RenderingFreeType
    VTK::RenderingContextOpenGL2 VTK::RenderingAnnotation)
  if (TARGET Vis4GS::FiltersGenealogy)
    target_compile_definitions(vis4gs PRIVATE VIS4GS_HAVE_GENEALOGY_FILTER)
  endif ()
  set(VIS4GS_HAVE_VIEW_COMMAND ON)
else ()
  message(STATUS "vis4gs: Qt5 Widgets or VTK::GUISupportQt not found, `vis4gs view` is left out")
  set(VIS4GS_HAVE_VIEW_COMMAND OFF)
endif ()

# A small SYNTHETIC training log for the application tests and benchmarks.
add_executable(vis4gsMakeTestLog vis4gsMakeTestLog.cxx)
target_compile_options(vis4gsMakeTestLog PRIVATE ${vis4gs_warning_flags})
target_link_libraries(vis4gsMakeTestLog PRIVATE vis4gs::CoreTrainingLog vis4gs::CoreGenealogy)

if (BUILD_TESTING AND VIS4GS_HAVE_VIEW_COMMAND)
  set(_vis4gs_view_dir "${CMAKE_CURRENT_BINARY_DIR}/Testing/view")
  add_test(NAME vis4gs-ViewMakeLog
    COMMAND vis4gsMakeTestLog "${_vis4gs_view_dir}/synthetic.h5" 400 4)
  add_test(NAME vis4gs-ViewEndToEnd
    COMMAND vis4gs view "${_vis4gs_view_dir}/synthetic.h5"
      "--self-test=${_vis4gs_view_dir}/screenshots" --resolution=1200,800)
  set_tests_properties(vis4gs-ViewMakeLog PROPERTIES LABELS "Application;GUI"
    FIXTURES_SETUP vis4gsViewLog)
  set_tests_properties(vis4gs-ViewEndToEnd PROPERTIES LABELS "Application;GUI"
    FIXTURES_REQUIRED vis4gsViewLog
    PASS_REGULAR_EXPRESSION "self-test passed" FAIL_REGULAR_EXPRESSION "FAILED")
  # The embedded demo log (cameras, images, genealogy): the floater case study end to end,
  # with baseline images of the scene and tree views (tolerant comparison, Xvfb + llvmpipe),
  # opened as `vis4gs demo` opens it (with the welcome panel).
  add_test(NAME vis4gs-ViewDemoEndToEnd
    COMMAND vis4gs view "${PROJECT_SOURCE_DIR}/Data/Demo/vis4gs-demo.h5"
      "--self-test=${_vis4gs_view_dir}/demo-screenshots" --resolution=1200,800 --welcome
      "--baseline=${CMAKE_CURRENT_SOURCE_DIR}/Testing/Data/Baseline")
  set_tests_properties(vis4gs-ViewDemoEndToEnd PROPERTIES LABELS "Application;GUI"
    PASS_REGULAR_EXPRESSION "self-test passed" FAIL_REGULAR_EXPRESSION "FAILED")
  # A scene file with cameras (issue 21): the demo's last snapshot as a PLY (analyze writes
  # it) with its training cameras as cameras.json beside it, found by the view on its own:
  # the layout without tree and timeline, View Coverage and the frustum check.
  set(_vis4gs_scene_dir "${_vis4gs_view_dir}/scene-with-cameras")
  add_test(NAME vis4gs-ViewMakeSceneWithCameras
    COMMAND "${CMAKE_COMMAND}" -E env PYTHONDONTWRITEBYTECODE=1
      "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/Testing/LogCamerasJson.py"
      "${PROJECT_SOURCE_DIR}/Data/Demo/vis4gs-demo.h5" "${_vis4gs_scene_dir}/cameras.json")
  add_test(NAME vis4gs-ViewMakeScenePly
    COMMAND vis4gs analyze "${PROJECT_SOURCE_DIR}/Data/Demo/vis4gs-demo.h5" --scores=shape
      "--output=${_vis4gs_scene_dir}")
  set_tests_properties(vis4gs-ViewMakeSceneWithCameras vis4gs-ViewMakeScenePly PROPERTIES
    LABELS "Application;GUI" FIXTURES_SETUP vis4gsSceneWithCameras)
  set_tests_properties(vis4gs-ViewMakeSceneWithCameras PROPERTIES
    PASS_REGULAR_EXPRESSION "wrote 29 training cameras")
  add_test(NAME vis4gs-ViewSceneWithCameras
    COMMAND vis4gs view "${_vis4gs_scene_dir}/scores.ply"
      "--self-test=${_vis4gs_scene_dir}/screenshots" --resolution=1280,800)
  set_tests_properties(vis4gs-ViewSceneWithCameras PROPERTIES LABELS "Application;GUI"
    FIXTURES_REQUIRED vis4gsSceneWithCameras
    PASS_REGULAR_EXPRESSION "the tree view is hidden.*the timeline view is hidden.*View Coverage was computed.*self-test passed"
    FAIL_REGULAR_EXPRESSION "FAILED")
  # The selection modes on real scenes (issue 15): Single's pick is on the Ray at a grid of
  # pixels of several views, and the floater case study's selections, on each file of the
  # shared data. The guard skips with exit code 77 and a message naming a missing file, and
  # fails when CI=true (vis4gs_shared_data_tests).
  set(_vis4gs_guard "${CMAKE_CURRENT_SOURCE_DIR}/Testing/RunIfPresent.sh")
  foreach (_vis4gs_real
      "PointCloudPly|inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply"
      "ModelSplat|inria_ply_tiny_kacytran/model_1.splat"
      "DonutSh0Ply|gs_ply_sh0_variant_donut_v3dg/fused.ply")
    string(REPLACE "|" ";" _vis4gs_pair "${_vis4gs_real}")
    list(GET _vis4gs_pair 0 _vis4gs_name)
    list(GET _vis4gs_pair 1 _vis4gs_file)
    add_test(NAME vis4gs-ViewSelfTest-${_vis4gs_name}
      COMMAND sh "${_vis4gs_guard}" "${VIS4GS_SHARED_DATA_DIR}/${_vis4gs_file}"
        "$<TARGET_FILE:vis4gs>" view "${VIS4GS_SHARED_DATA_DIR}/${_vis4gs_file}"
        "--self-test=${_vis4gs_view_dir}/selftest-${_vis4gs_name}" --resolution=1200,800)
    set_tests_properties(vis4gs-ViewSelfTest-${_vis4gs_name} PROPERTIES
      LABELS "Application;GUI" FAIL_REGULAR_EXPRESSION "FAILED")
    vis4gs_shared_data_tests(vis4gs-ViewSelfTest-${_vis4gs_name})
  endforeach ()
  # A compressed PLY (issue 19) written from the INRIA PLY by our writer, opened by content.
  if (TARGET vis4gsSceneConvert)
    set(_vis4gs_compressed "${_vis4gs_view_dir}/inria.compressed.ply")
    set(_vis4gs_inria "${VIS4GS_SHARED_DATA_DIR}/inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply")
    add_test(NAME vis4gs-ViewMakeCompressedPly
      COMMAND sh "${_vis4gs_guard}" "${_vis4gs_inria}" $<TARGET_FILE:vis4gsSceneConvert>
        "${_vis4gs_inria}" "${_vis4gs_compressed}" --compressed)
    set_tests_properties(vis4gs-ViewMakeCompressedPly PROPERTIES LABELS "Application;GUI"
      FIXTURES_SETUP vis4gsCompressedPly PASS_REGULAR_EXPRESSION "9080 Gaussians written")
    add_test(NAME vis4gs-ViewSelfTest-CompressedPly
      COMMAND sh "${_vis4gs_guard}" "${_vis4gs_inria}" "$<TARGET_FILE:vis4gs>" view
        "${_vis4gs_compressed}" "--self-test=${_vis4gs_view_dir}/selftest-CompressedPly"
        --resolution=1200,800)
    set_tests_properties(vis4gs-ViewSelfTest-CompressedPly PROPERTIES LABELS "Application;GUI"
      FIXTURES_REQUIRED vis4gsCompressedPly PASS_REGULAR_EXPRESSION "self-test passed"
      FAIL_REGULAR_EXPRESSION "FAILED")
    vis4gs_shared_data_tests(vis4gs-ViewMakeCompressedPly vis4gs-ViewSelfTest-CompressedPly)
  endif ()
  # Extreme shapes generated at test time: needles, disks, huge and tiny scales, opacity 0
  # and 1, means at the near plane of one of its two cameras.
  set(_vis4gs_extreme_dir "${_vis4gs_view_dir}/extreme")
  add_test(NAME vis4gs-ViewMakeExtremeScene
    COMMAND "${CMAKE_COMMAND}" -E env PYTHONDONTWRITEBYTECODE=1
      "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/Testing/MakeExtremeScene.py"
      "${_vis4gs_extreme_dir}")
  set_tests_properties(vis4gs-ViewMakeExtremeScene PROPERTIES LABELS "Application;GUI"
    FIXTURES_SETUP vis4gsExtremeScene PASS_REGULAR_EXPRESSION "wrote 3000 Gaussians")
  add_test(NAME vis4gs-ViewSelfTest-ExtremeScene
    COMMAND vis4gs view "${_vis4gs_extreme_dir}/extreme.ply"
      "--self-test=${_vis4gs_extreme_dir}/screenshots" --resolution=1200,800)
  set_tests_properties(vis4gs-ViewSelfTest-ExtremeScene PROPERTIES LABELS "Application;GUI"
    FIXTURES_REQUIRED vis4gsExtremeScene
    PASS_REGULAR_EXPRESSION "Single's pick is on the Ray at [0-9]+ of [0-9]+ pixels of 5 views.*self-test passed"
    FAIL_REGULAR_EXPRESSION "FAILED")
  # The special-value table (Documentation/special-values.md) through the commands: render's
  # and analyze's per-reason counts equal numpy's on the raw floats, and what is skipped
  # leaves no pixel changed.
  add_test(NAME vis4gs-SpecialValuesCommands
    COMMAND "${CMAKE_COMMAND}" -E env PYTHONDONTWRITEBYTECODE=1
      "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/Testing/CheckSpecialValues.py"
      "$<TARGET_FILE:vis4gs>" "${_vis4gs_extreme_dir}/extreme.ply"
      "${_vis4gs_extreme_dir}/special-values")
  set_tests_properties(vis4gs-SpecialValuesCommands PROPERTIES LABELS "Application"
    FIXTURES_REQUIRED vis4gsExtremeScene
    PASS_REGULAR_EXPRESSION "special values checked: 3005 Gaussians, 3000 drawn"
    FAIL_REGULAR_EXPRESSION "FAILED")
  # The benchmark mode runs (figures of real sizes: Documentation/performance.md).
  add_test(NAME vis4gs-ViewBenchmarkMode
    COMMAND vis4gs view "${_vis4gs_view_dir}/synthetic.h5" --benchmark --resolution=800,600)
  set_tests_properties(vis4gs-ViewBenchmarkMode PROPERTIES LABELS "Application;GUI"
    FIXTURES_REQUIRED vis4gsViewLog
    PASS_REGULAR_EXPRESSION "start to all views ready.*tree pan/zoom at the overview")
  add_test(NAME vis4gs-ViewHelp COMMAND vis4gs view --help)
  set_tests_properties(vis4gs-ViewHelp PROPERTIES LABELS "Application"
    PASS_REGULAR_EXPRESSION "--self-test=DIR")
endif ()
