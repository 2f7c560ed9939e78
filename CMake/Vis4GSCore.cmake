# Helpers for the VTK-free Core libraries (DESIGN §1): plain C++17 static libraries with
# position-independent code, unit-tested with GoogleTest.

# Flags for code we write (never for VTK's generated wrapping code).
set(vis4gs_warning_flags -Wall -Wextra)
if (VIS4GS_WARNINGS_AS_ERRORS)
  list(APPEND vis4gs_warning_flags -Werror)
endif ()

# vis4gs_add_core_library(<name> SOURCES ... [DEPENDS ...] [PRIVATE_DEPENDS ...])
# Creates target vis4gsCore<name> with alias vis4gs::Core<name>; headers are included as
# "<Name>.h" from the library's folder.
function (vis4gs_add_core_library name)
  cmake_parse_arguments(arg "" "" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  set(target "vis4gsCore${name}")
  add_library(${target} STATIC ${arg_SOURCES})
  add_library(vis4gs::Core${name} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    "$<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}>"
    "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/vis4gs>")
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_compile_options(${target} PRIVATE ${vis4gs_warning_flags})
  target_link_libraries(${target} PUBLIC ${arg_DEPENDS} PRIVATE ${arg_PRIVATE_DEPENDS})
  # VTK modules link Core publicly, so Core joins their export set.
  install(TARGETS ${target} EXPORT Vis4GSTargets ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")
endfunction ()

# vis4gs_add_core_test(<name> SOURCES ... DEPENDS ...)
# One GoogleTest executable per Core folder; every TEST becomes its own CTest test named
# Core<name>.<Suite>.<Test>, labelled Core and Core<name>.
function (vis4gs_add_core_test name)
  if (NOT BUILD_TESTING)
    return ()
  endif ()
  cmake_parse_arguments(arg "" "" "SOURCES;DEPENDS" ${ARGN})
  set(target "vis4gsCore${name}Tests")
  add_executable(${target} ${arg_SOURCES})
  target_compile_options(${target} PRIVATE ${vis4gs_warning_flags})
  target_link_libraries(${target} PRIVATE ${arg_DEPENDS} vis4gs::TestingCore GTest::gtest_main)
  gtest_discover_tests(${target}
    TEST_PREFIX "Core${name}."
    PROPERTIES LABELS "Core;Core${name}" SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]"
    DISCOVERY_TIMEOUT 60)
  # The TESTs that start with VIS4GS_REQUIRE_SHARED_DATA() read ../shared/data: label them
  # SharedData once discovery has added them (an include file that runs after gtest's).
  set(_shared)
  foreach (_source IN LISTS arg_SOURCES)
    get_filename_component(_path "${_source}" ABSOLUTE)
    file(STRINGS "${_path}" _lines REGEX "^TEST(_F|_P)?\\(|VIS4GS_REQUIRE_SHARED_DATA\\(\\)")
    set(_test)
    foreach (_line IN LISTS _lines)
      if (_line MATCHES "^TEST(_F|_P)?\\(([A-Za-z0-9_]+), *([A-Za-z0-9_]+)\\)")
        set(_test "Core${name}.${CMAKE_MATCH_2}.${CMAKE_MATCH_3}")
      elseif (_test)
        list(APPEND _shared "${_test}")
      endif ()
    endforeach ()
  endforeach ()
  if (_shared)
    set(_include "${CMAKE_CURRENT_BINARY_DIR}/${target}_shared_data.cmake")
    set(_content "")
    foreach (_test IN LISTS _shared)
      string(APPEND _content
        "set_tests_properties(\"${_test}\" PROPERTIES LABELS \"Core;Core${name};SharedData\")\n")
    endforeach ()
    file(WRITE "${_include}" "${_content}")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${_include}")
  endif ()
endfunction ()

# vis4gs_shared_data_tests(<test>...)
# Marks tests that read the real third-party data in VIS4GS_SHARED_DATA_DIR (../shared/data
# beside the checkout): label SharedData, exit status 77 reported as skipped (what
# Testing/Core's VIS4GS_SHARED_DATA_OR_SKIP() and Applications' RunIfPresent.sh return). When
# the folder is absent at configure time they are disabled (CTest lists them as not run), and
# the test Vis4GS-SharedData says which folder is missing; with CI=true they stay enabled and
# fail, as does Vis4GS-SharedData.
function (vis4gs_shared_data_tests)
  foreach (_test IN LISTS ARGN)
    set_property(TEST "${_test}" APPEND PROPERTY LABELS SharedData)
    set_property(TEST "${_test}" PROPERTY SKIP_RETURN_CODE 77)
    if (NOT EXISTS "${VIS4GS_SHARED_DATA_DIR}" AND NOT "$ENV{CI}" STREQUAL "true")
      set_property(TEST "${_test}" PROPERTY DISABLED TRUE)
    endif ()
  endforeach ()
endfunction ()

# vis4gs_add_benchmark(<name> SOURCES ... DEPENDS ...)
# Benchmarks are programs that print figures; they are built, never run by CTest.
function (vis4gs_add_benchmark name)
  cmake_parse_arguments(arg "" "" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${arg_SOURCES})
  target_compile_options(${name} PRIVATE ${vis4gs_warning_flags})
  target_link_libraries(${name} PRIVATE ${arg_DEPENDS})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/benchmarks")
endfunction ()
