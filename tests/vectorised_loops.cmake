# build.vectorised_loops: each loop that follows an RT_VECTOR_LOOP line in include/ and
# src/ is vectorised by GCC wherever it is compiled. The render units of raytracer_core
# are compiled again, with their commands from BUILD_DIR/compile_commands.json, adding
# GCC's -fopt-info-vec-optimized-missed report, which names each instance of a loop as
# "<file>:<line>:<column>: optimized: loop vectorized" or "...: missed: couldn't
# vectorize loop"; a marked loop must have the first and never the second (a
# template's loop is reported once per instantiation). A loop GCC keeps scalar gives
# the same bytes, so only this test notices it (the eye-ray loop once ran scalar for two
# days, 2x slower).
#   cmake -DSOURCE_DIR=<repository> -DBUILD_DIR=<build> -DWORK_DIR=<scratch> -P vectorised_loops.cmake
cmake_minimum_required(VERSION 3.20)

# The reports: each render unit of raytracer_core compiled as the build does, into WORK_DIR
# (GCC appends to a report file, so each is written afresh).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(READ "${BUILD_DIR}/compile_commands.json" commands)
string(JSON count LENGTH "${commands}")
math(EXPR last "${count} - 1")
set(reports "")
foreach(i RANGE ${last})
  string(JSON command GET "${commands}" ${i} command)
  if(NOT command MATCHES "raytracer_core\\.dir/src/(render_tree|flat_sweep/render_flat_sweep)\\.cpp\\.o")
    continue()
  endif()
  string(MAKE_C_IDENTIFIER "${CMAKE_MATCH_1}" unit)
  set(report "${WORK_DIR}/${unit}.txt")
  string(JSON directory GET "${commands}" ${i} directory)
  separate_arguments(arguments UNIX_COMMAND "${command}")
  list(FIND arguments "-o" at)
  math(EXPR at "${at} + 1")
  list(REMOVE_AT arguments ${at})
  list(INSERT arguments ${at} "${WORK_DIR}/${unit}.o")
  execute_process(COMMAND ${arguments} "-fopt-info-vec-optimized-missed=${report}"
                  WORKING_DIRECTORY "${directory}" RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "compiling ${unit} failed")
  endif()
  list(APPEND reports "${report}")
endforeach()
list(LENGTH reports units)
if(NOT units EQUAL 2)
  message(FATAL_ERROR "expected the 2 render units of raytracer_core in ${BUILD_DIR}/compile_commands.json, found ${units}")
endif()

set(vectorised "")
set(kept_scalar "")
foreach(report IN LISTS reports)
  file(STRINGS "${report}" lines REGEX ": (optimized: loop vectorized|missed: couldn't vectorize loop)")
  foreach(line IN LISTS lines)
    string(REGEX MATCH "^([^:]+):([0-9]+):[0-9]+: ([a-z]+)" place "${line}")
    get_filename_component(file "${CMAKE_MATCH_1}" REALPATH)
    if(CMAKE_MATCH_3 STREQUAL "optimized")
      list(APPEND vectorised "${file}:${CMAKE_MATCH_2}")
    else()
      list(APPEND kept_scalar "${file}:${CMAKE_MATCH_2}")
    endif()
  endforeach()
endforeach()

# The marked loops: the line after each RT_VECTOR_LOOP line.
file(GLOB_RECURSE sources "${SOURCE_DIR}/include/*.h" "${SOURCE_DIR}/src/*.cpp")
set(marked 0)
set(scalar "")
foreach(source IN LISTS sources)
  get_filename_component(source "${source}" REALPATH)
  # One list element per line: ';' and brackets, which CMake's lists treat specially,
  # replaced first.
  file(READ "${source}" text)
  string(REGEX REPLACE "[][;]" "_" text "${text}")
  string(REPLACE "\n" ";" text "${text}")
  set(number 0)
  set(next_is_marked FALSE)
  foreach(line IN LISTS text)
    math(EXPR number "${number} + 1")
    if(next_is_marked)
      math(EXPR marked "${marked} + 1")
      if(NOT "${source}:${number}" IN_LIST vectorised OR "${source}:${number}" IN_LIST kept_scalar)
        list(APPEND scalar "${source}:${number}")
      endif()
    endif()
    set(next_is_marked FALSE)
    if(line MATCHES "^[ \t]*RT_VECTOR_LOOP[ \t]*$")
      set(next_is_marked TRUE)
    endif()
  endforeach()
endforeach()

if(marked EQUAL 0)
  message(FATAL_ERROR "no loop marked RT_VECTOR_LOOP found under ${SOURCE_DIR}")
endif()
if(scalar)
  list(JOIN scalar "\n  " shown)
  message(FATAL_ERROR "GCC did not vectorise these marked loops (or not in every instance):\n  ${shown}")
endif()
message(STATUS "${marked} marked loops, all vectorised")
