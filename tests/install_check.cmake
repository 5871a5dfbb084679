# `cmake --install` puts raytracer.exe in <prefix>/bin, and the installed program runs.
#   cmake -DBUILD_DIR=... -DCONFIG=... -DPREFIX=... -DVERSION=... [-DEMULATOR=...] -P install_check.cmake
foreach(variable BUILD_DIR PREFIX VERSION)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "install_check.cmake: ${variable} is not set")
  endif()
endforeach()

file(REMOVE_RECURSE "${PREFIX}")
set(config_arguments)
if(CONFIG)
  set(config_arguments --config "${CONFIG}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}" ${config_arguments}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${status}")
endif()

set(installed "${PREFIX}/bin/raytracer.exe")
if(NOT EXISTS "${installed}")
  message(FATAL_ERROR "cmake --install did not put raytracer.exe in ${PREFIX}/bin")
endif()
execute_process(COMMAND ${EMULATOR} "${installed}" --version RESULT_VARIABLE status OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
string(REPLACE "\r\n" "\n" out "${out}")
if(NOT status EQUAL 0 OR NOT out STREQUAL "raytracer.exe ${VERSION}\n")
  message(FATAL_ERROR "the installed raytracer.exe --version: status '${status}', printed '${out}' '${err}', "
                      "expected status 0 and 'raytracer.exe ${VERSION}'")
endif()
file(REMOVE_RECURSE "${PREFIX}")
message(STATUS "installed ${installed}: ${out}")
