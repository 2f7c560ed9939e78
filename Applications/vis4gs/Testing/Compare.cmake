# `vis4gs compare` (issue 20), included from this folder's CMakeLists.txt. CheckCompare.py
# recomputes differences.csv from the log's snapshots with numpy (two iterations of the demo
# log), and checks a scene against its cleaned copy from analyze --select --delete.
set(_vis4gs_compare_log "${PROJECT_SOURCE_DIR}/Data/Demo/vis4gs-demo.h5")
add_test(NAME vis4gs-CompareIterations
  COMMAND "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/CheckCompare.py"
    $<TARGET_FILE:vis4gs> "${CMAKE_CURRENT_BINARY_DIR}/compare-iterations" log
    "${_vis4gs_compare_log}")
add_test(NAME vis4gs-CompareCleaned
  COMMAND "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/CheckCompare.py"
    $<TARGET_FILE:vis4gs> "${CMAKE_CURRENT_BINARY_DIR}/compare-cleaned" ply
    "${CMAKE_CURRENT_BINARY_DIR}/analyze-cleanup-floaters" "${_vis4gs_compare_log}")
set_tests_properties(vis4gs-CompareIterations vis4gs-CompareCleaned PROPERTIES
  LABELS "Application;Python" PASS_REGULAR_EXPRESSION "compare outputs agree with numpy"
  FAIL_REGULAR_EXPRESSION "FAILED")
set_tests_properties(vis4gs-CompareCleaned PROPERTIES FIXTURES_REQUIRED vis4gsCleanup-floaters)
vis4gs_add_app_test(CompareMissingInput ARGS compare "${_vis4gs_compare_log}" no-such-scene.ply
  --output=${CMAKE_CURRENT_BINARY_DIR}/compare-missing STATUS 1 OUTPUT "no-such-scene.ply"
  ABSENT ${CMAKE_CURRENT_BINARY_DIR}/compare-missing)
vis4gs_add_app_test(CompareBadThreshold ARGS compare "${_vis4gs_compare_log}"
  "${_vis4gs_compare_log}" --move=-1 --output=${CMAKE_CURRENT_BINARY_DIR}/compare-bad
  STATUS 1 OUTPUT "--move, --opacity and --scale must be >= 0"
  ABSENT ${CMAKE_CURRENT_BINARY_DIR}/compare-bad)
