# `vis4gs convert` (issue 34): every pair of the formats it writes, the reported quantisation
# against the measured one, --sh-degree, --no-extras and bad arguments (CheckConvert.py).
add_test(NAME vis4gs-Convert
  COMMAND "${VIS4GS_SYSTEM_PYTHON}" "${CMAKE_CURRENT_SOURCE_DIR}/CheckConvert.py"
    $<TARGET_FILE:vis4gs> "${CMAKE_CURRENT_BINARY_DIR}/convert")
set_tests_properties(vis4gs-Convert PROPERTIES LABELS "Application"
  ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1" FAIL_REGULAR_EXPRESSION "FAILED" TIMEOUT 600)
