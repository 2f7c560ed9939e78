# `vis4gs compare` and `vis4gs repair` (issue 20), included from this folder's CMakeLists.txt. CheckCompare.py
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
  LABELS "Application;Python" FAIL_REGULAR_EXPRESSION "FAILED")
set_tests_properties(vis4gs-CompareCleaned PROPERTIES FIXTURES_REQUIRED vis4gsCleanup-floaters)
vis4gs_add_app_test(CompareMissingInput ARGS compare "${_vis4gs_compare_log}" no-such-scene.ply
  --output=${CMAKE_CURRENT_BINARY_DIR}/compare-missing STATUS 1 OUTPUT "no-such-scene.ply"
  ABSENT ${CMAKE_CURRENT_BINARY_DIR}/compare-missing)
vis4gs_add_app_test(CompareBadThreshold ARGS compare "${_vis4gs_compare_log}"
  "${_vis4gs_compare_log}" --move=-1 --output=${CMAKE_CURRENT_BINARY_DIR}/compare-bad
  STATUS 1 OUTPUT "--move, --opacity and --scale must be >= 0"
  ABSENT ${CMAKE_CURRENT_BINARY_DIR}/compare-bad)

# `vis4gs repair` (issue 20): the cleaned scene of analyze --select="views<=3" --delete
# fine-tuned 50 iterations; CheckRepair.py reads repaired.h5 with h5py and the genealogy filter.
add_test(NAME vis4gs-RepairCleaned
  COMMAND "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/CheckRepair.py"
    $<TARGET_FILE:vis4gs> "${_vis4gs_compare_log}"
    "${CMAKE_CURRENT_BINARY_DIR}/analyze-cleanup-floaters" "${CMAKE_CURRENT_BINARY_DIR}/repair")
set_tests_properties(vis4gs-RepairCleaned PROPERTIES LABELS "Application;Python"
  ENVIRONMENT "PYTHONPATH=${VIS4GS_PYTHONPATH};PYTHONDONTWRITEBYTECODE=1"
  FAIL_REGULAR_EXPRESSION "FAILED"
  FIXTURES_REQUIRED vis4gsCleanup-floaters)
# A cleaned scene that is no subset of the snapshot (iteration 400 lacks most of its ids).
vis4gs_add_app_test(RepairWrongSnapshot ARGS repair "${_vis4gs_compare_log}"
  "${CMAKE_CURRENT_BINARY_DIR}/analyze-cleanup-floaters/cleaned.ply" --iteration=400
  --output=${CMAKE_CURRENT_BINARY_DIR}/repair-wrong STATUS 1
  OUTPUT "cleaned.ply: holds [0-9]+ ids that the snapshot of iteration 400"
  ABSENT ${CMAKE_CURRENT_BINARY_DIR}/repair-wrong)
set_tests_properties(vis4gs-RepairWrongSnapshot PROPERTIES
  FIXTURES_REQUIRED vis4gsCleanup-floaters)
# `vis4gs repair SCENE.ply CLEANED` (issue 20): the demo log's last snapshot as a PLY with ids,
# its cameras.json and PNG images (made with numpy/zlib), repaired 2 iterations like the log;
# also the Python layer's Scene.repair on that scene and the errors.
add_test(NAME vis4gs-RepairScene
  COMMAND "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/CheckRepairScene.py"
    $<TARGET_FILE:vis4gs> "${_vis4gs_compare_log}"
    "${CMAKE_CURRENT_BINARY_DIR}/analyze-cleanup-floaters" "${CMAKE_CURRENT_BINARY_DIR}/repair-scene")
set_tests_properties(vis4gs-RepairScene PROPERTIES LABELS "Application;Python"
  ENVIRONMENT "PYTHONPATH=${VIS4GS_PYTHONPATH};PYTHONDONTWRITEBYTECODE=1"
  FAIL_REGULAR_EXPRESSION "FAILED"
  FIXTURES_REQUIRED vis4gsCleanup-floaters)
# Its scene, cameras, images and repair run are the clean-up panel's scene-file test's
# (vis4gs-ViewCleanupScene, ../vis4gsView.cmake).
set_tests_properties(vis4gs-RepairScene PROPERTIES FIXTURES_SETUP vis4gsRepairScene)
