# `cmake --install` puts raytracer.exe and raytracer-grade in <prefix>/bin, and the
# installed programs run: the grader finds raytracer.exe beside itself and, where the
# course scenes are (SCENES), grades one with it.
#   cmake -DBUILD_DIR=... -DCONFIG=... -DPREFIX=... -DVERSION=... [-DEXE_SUFFIX=.exe] [-DSCENES=dir]
#         [-DEMULATOR=...] -P install_check.cmake
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

set(grader "${PREFIX}/bin/raytracer-grade${EXE_SUFFIX}")
if(NOT EXISTS "${grader}")
  message(FATAL_ERROR "cmake --install did not put raytracer-grade${EXE_SUFFIX} in ${PREFIX}/bin")
endif()
execute_process(COMMAND ${EMULATOR} "${grader}" --help RESULT_VARIABLE status OUTPUT_VARIABLE help)
if(NOT status EQUAL 0 OR NOT help MATCHES "^usage: raytracer-grade")
  message(FATAL_ERROR "the installed raytracer-grade --help: status '${status}', printed '${help}'")
endif()
if(SCENES AND IS_DIRECTORY "${SCENES}")
  execute_process(COMMAND ${EMULATOR} "${grader}" --only testAmbient "${SCENES}" RESULT_VARIABLE status
                  OUTPUT_VARIABLE graded ERROR_VARIABLE err)
  string(REPLACE "\r\n" "\n" graded "${graded}")
  if(NOT status EQUAL 0 OR NOT graded MATCHES "marks 2/2: the scene passes: PASS")
    message(FATAL_ERROR "the installed raytracer-grade, grading testAmbient with the raytracer.exe beside it: "
                        "status '${status}', printed '${graded}' '${err}'")
  endif()
endif()
file(REMOVE_RECURSE "${PREFIX}")
message(STATUS "installed ${installed}: ${out}")
message(STATUS "installed ${grader}")
