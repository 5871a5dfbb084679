# build.source_layers: the architecture the folders show, checked on the sources.
# - The reference path (include/raytracer/reference/) reads on its own: its headers
#   include each other and a few plain headers (the vector, the scene, the image,
#   compiler hints, large arrays), never a fast path's (accel/, flat_sweep/) nor the
#   vector lanes (lanes.h), which the fast paths build on it.
# - No file of src/ or include/ (the grader aside) is over 400 lines: one screen of
#   ideas a file, split before it grows past that.
#   cmake -DSOURCE_DIR=<repository> -P source_layers.cmake
cmake_minimum_required(VERSION 3.20)

set(plain_headers compiler.h image.h large_pages.h scene.h scene_precision.h vec3.h)
set(problems "")
file(GLOB reference_headers "${SOURCE_DIR}/include/raytracer/reference/*.h")
if(NOT reference_headers)
  message(FATAL_ERROR "no headers in ${SOURCE_DIR}/include/raytracer/reference")
endif()
foreach(header IN LISTS reference_headers)
  file(STRINGS "${header}" includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${line}")
    string(REGEX REPLACE "^raytracer/" "" name "${included}")
    if(name MATCHES "^reference/[^/]+\\.h$")
      continue()
    endif()
    list(FIND plain_headers "${name}" at)
    if(at EQUAL -1)
      file(RELATIVE_PATH shown "${SOURCE_DIR}" "${header}")
      list(APPEND problems "${shown} includes ${included}, outside the reference and its plain headers")
    endif()
  endforeach()
endforeach()

file(GLOB_RECURSE sources "${SOURCE_DIR}/src/*.cpp" "${SOURCE_DIR}/src/*.h" "${SOURCE_DIR}/include/*.h")
list(FILTER sources EXCLUDE REGEX "/src/grade/")
foreach(source IN LISTS sources)
  file(RELATIVE_PATH shown "${SOURCE_DIR}" "${source}")
  file(READ "${source}" text)
  string(REGEX MATCHALL "\n" newlines "${text}")
  list(LENGTH newlines count)
  if(count GREATER 400)
    list(APPEND problems "${shown} has ${count} lines, over 400")
  endif()
endforeach()

if(problems)
  list(JOIN problems "\n  " shown)
  message(FATAL_ERROR "source layers:\n  ${shown}")
endif()
list(LENGTH reference_headers headers)
list(LENGTH sources files)
message(STATUS "reference/: ${headers} headers on their own; ${files} files of src/ and include/ checked for length")
