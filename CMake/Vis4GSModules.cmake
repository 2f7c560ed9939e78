# Scans, builds and wraps every VTK module of the project (folders with a vtk.module file).
# See ../shared/guides/vtk-9.1.md §5 for the Debian VTK 9.1 traps handled here.

vtk_module_find_modules(vis4gs_module_files "${PROJECT_SOURCE_DIR}")
list(FILTER vis4gs_module_files EXCLUDE REGEX "/build[^/]*/")

vtk_module_scan(
  MODULE_FILES ${vis4gs_module_files}
  WANT_BY_DEFAULT ON
  PROVIDES_MODULES vis4gs_modules
  ENABLE_TESTS "${BUILD_TESTING}")

set(vis4gs_python_destination "")
if (TARGET VTK::Python AND TARGET VTK::WrappingPythonCore)
  set(VIS4GS_WRAP_PYTHON ON)
  vtk_module_python_default_destination(vis4gs_python_destination)
else ()
  set(VIS4GS_WRAP_PYTHON OFF)
endif ()

# Debian ships no VTK::vtkpython target; its interpreter is /usr/bin/vtkpython-9.0 (the
# plain python3 rejects the --enable-bt flag VTK's test macros add).
find_program(VIS4GS_VTKPYTHON NAMES vtkpython vtkpython-9.1 vtkpython-9.0 pvtkpython
  PATHS /usr/bin NO_DEFAULT_PATH)
set(_vtk_testing_python_exe "${VIS4GS_VTKPYTHON}")
set(VIS4GS_PYTHONPATH "${CMAKE_BINARY_DIR}/${vis4gs_python_destination}")

# vis4gs_add_python_test(<module> <script.py>... [ARGS ...])
# Runs each script with Debian's VTK Python (/usr/bin/python3) and the build tree's vis4gs
# package on PYTHONPATH; the test is named <module>Python-<script> and labelled like the
# module's C++ tests. Scripts exit non-zero and print "FAILED: ..." on failure.
function (vis4gs_add_python_test module)
  cmake_parse_arguments(arg "" "" "ARGS" ${ARGN})
  string(REPLACE "Vis4GS::" "vis4gs" _library "${module}")
  foreach (_script IN LISTS arg_UNPARSED_ARGUMENTS)
    get_filename_component(_name "${_script}" NAME_WE)
    add_test(NAME "${module}Python-${_name}"
      COMMAND /usr/bin/python3 "${CMAKE_CURRENT_SOURCE_DIR}/${_script}" ${arg_ARGS}
      WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
    set_tests_properties("${module}Python-${_name}" PROPERTIES
      ENVIRONMENT "PYTHONPATH=${VIS4GS_PYTHONPATH}:${PROJECT_SOURCE_DIR}/Testing/Python;VIS4GS_SHARED_DATA_DIR=${VIS4GS_SHARED_DATA_DIR};VIS4GS_SOURCE_DIR=${PROJECT_SOURCE_DIR};VIS4GS_BINARY_DIR=${CMAKE_BINARY_DIR}"
      LABELS "${_library};Python"
      FAIL_REGULAR_EXPRESSION "FAILED:;Traceback")
    # A script that reads ../shared/data (through Testing/Python's shared_data_dir()).
    file(READ "${CMAKE_CURRENT_SOURCE_DIR}/${_script}" _text)
    if (_text MATCHES "shared_data_dir\\(\\)")
      vis4gs_shared_data_tests("${module}Python-${_name}")
    endif ()
  endforeach ()
endfunction ()

# vis4gs_add_masked_baseline_tests(<module> <test> <compare option>...)
# The C++ image test <module>Cxx-<test> writes <test>-selected.png and <test>-unselected.png
# into its binary folder; this adds <...>-MaskedBaseline (the selected picture against
# Data/Baseline/<test>.png, strictly inside masks around the highlight colours given as
# options of Testing/Python/vis4gs_image_compare.py, loosely elsewhere) and
# <...>-MaskedBaselineNeedsHighlight (the unselected picture must fail there), both needing
# the image test (Documentation/dev/TESTING.md, masked baselines).
function (vis4gs_add_masked_baseline_tests module test)
  string(REPLACE "Vis4GS::" "vis4gs" _library "${module}")
  set(_setup "${module}Cxx-${test}")
  set_tests_properties("${_setup}" PROPERTIES FIXTURES_SETUP "${test}Images")
  foreach (_state IN ITEMS selected unselected)
    set(_name "${_setup}-MaskedBaseline")
    set(_expect)
    if (_state STREQUAL "unselected")
      set(_name "${_setup}-MaskedBaselineNeedsHighlight")
      set(_expect --expect-mismatch)
    endif ()
    add_test(NAME "${_name}"
      COMMAND "${VIS4GS_SYSTEM_PYTHON}"
        "${PROJECT_SOURCE_DIR}/Testing/Python/vis4gs_image_compare.py"
        "${CMAKE_CURRENT_SOURCE_DIR}/../Data/Baseline/${test}.png"
        "${CMAKE_CURRENT_BINARY_DIR}/${test}-${_state}.png"
        ${ARGN} ${_expect})
    set_tests_properties("${_name}" PROPERTIES
      LABELS "${module};${_library};Python"
      FIXTURES_REQUIRED "${test}Images" FAIL_REGULAR_EXPRESSION "FAILED:")
  endforeach ()
endfunction ()

vtk_module_build(
  MODULES ${vis4gs_modules}
  INSTALL_EXPORT Vis4GSTargets
  CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/vis4gs"
  VERSION "${PROJECT_VERSION}"
  SOVERSION "0"
  TEST_INPUT_DATA_DIRECTORY "${PROJECT_SOURCE_DIR}"
  TEST_OUTPUT_DATA_DIRECTORY "${PROJECT_SOURCE_DIR}")

foreach (_vis4gs_module IN LISTS vis4gs_modules)
  get_property(_vis4gs_target GLOBAL PROPERTY "_vtk_module_${_vis4gs_module}_target_name")
  if (_vis4gs_target)
    target_compile_options(${_vis4gs_target} PRIVATE ${vis4gs_warning_flags})
  endif ()
endforeach ()

if (VIS4GS_WRAP_PYTHON)
  vtk_module_wrap_python(
    MODULES ${vis4gs_modules}
    PYTHON_PACKAGE "vis4gs"
    MODULE_DESTINATION "${vis4gs_python_destination}"
    INSTALL_EXPORT Vis4GSPython
    CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/vis4gs"
    BUILD_STATIC OFF
    INSTALL_HEADERS OFF)
  add_subdirectory("${PROJECT_SOURCE_DIR}/Wrapping/Python" "${CMAKE_BINARY_DIR}/Wrapping/Python")
endif ()
