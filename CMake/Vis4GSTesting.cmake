# vis4gs_add_checked_test(<test> [STATUS n] [OUTPUT regex] [FILES path...] [PNG path:w,h...]
#   [ABSENT path...] [LABELS label...] COMMAND command...)
# Every test that needs a line of its output runs through Testing/RunCommand.py, which checks
# the exit status first (always: an error message can print any text, and CTest's
# PASS_REGULAR_EXPRESSION ignores the exit status, so no test uses it), then the files the
# command claims to write (removed before the run) or must not leave, then the OUTPUT regex
# for the claim a line carries (a count, the number of MPI processes). Used by the main build
# and by the ParaView plugin's build (Plugins/ParaView). Documentation/dev/TESTING.md.
if (NOT VIS4GS_SYSTEM_PYTHON)
  set(VIS4GS_SYSTEM_PYTHON "/usr/bin/python3")
endif ()
set(VIS4GS_RUN_COMMAND "${CMAKE_CURRENT_LIST_DIR}/../Testing/RunCommand.py")
get_filename_component(VIS4GS_RUN_COMMAND "${VIS4GS_RUN_COMMAND}" ABSOLUTE)

function (vis4gs_add_checked_test name)
  cmake_parse_arguments(arg "" "STATUS;OUTPUT;IF_PRESENT" "FILES;PNG;ABSENT;LABELS;COMMAND" ${ARGN})
  set(_checks "--status=0")
  if (DEFINED arg_STATUS)
    set(_checks "--status=${arg_STATUS}")
  endif ()
  if (DEFINED arg_OUTPUT)
    list(APPEND _checks "--output=${arg_OUTPUT}")
  endif ()
  foreach (_path IN LISTS arg_FILES)
    list(APPEND _checks "--file=${_path}")
  endforeach ()
  foreach (_path IN LISTS arg_PNG)
    list(APPEND _checks "--png=${_path}")
  endforeach ()
  foreach (_path IN LISTS arg_ABSENT)
    list(APPEND _checks "--absent=${_path}")
  endforeach ()
  if (NOT arg_LABELS)
    set(arg_LABELS "Application")
  endif ()
  # A test of shared data checks at run time that the data is there (RunIfPresent.sh exits 77
  # naming it, 1 under CI=true): the folder can go after configuring, and RunCommand's status
  # check would otherwise report its absence as the command's failure.
  set(_guard)
  if (DEFINED arg_IF_PRESENT)
    set(_guard sh "${PROJECT_SOURCE_DIR}/Applications/vis4gs/Testing/RunIfPresent.sh"
      "${arg_IF_PRESENT}")
  endif ()
  add_test(NAME "${name}"
    COMMAND ${_guard} "${VIS4GS_SYSTEM_PYTHON}" "${VIS4GS_RUN_COMMAND}" ${_checks} -- ${arg_COMMAND}
    WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  set_tests_properties("${name}" PROPERTIES LABELS "${arg_LABELS}"
    ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1" FAIL_REGULAR_EXPRESSION "FAILED:")
endfunction ()
