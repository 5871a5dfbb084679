# Starts or stops the Wine session that the tests of a cross build run in.
#   cmake -DACTION=start|stop -DWINE=... -DWINESERVER=... -DLOG_DIR=... -P wine_session.cmake
# The caller sets WINEPREFIX.
#
# Why: the first Windows process of a Wine session starts Wine's services, among them
# the mount manager, which sets up the drive letters; a process started meanwhile can
# fail to see Z: (cmd.exe: "Can't recognize ... as an internal or external command",
# or std::system returning -1), measured here in about 1 CTest run in 10. So "start"
# starts a persistent Wine server, lets wineboot make the prefix and bring the session
# up, and runs one Windows program in it before any test runs; the session stays up
# until "stop".
foreach(variable ACTION WINE WINESERVER LOG_DIR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "wine_session.cmake: ${variable} is not set")
  endif()
endforeach()

if(ACTION STREQUAL "stop")
  execute_process(COMMAND "${WINESERVER}" --kill)
  execute_process(COMMAND "${WINESERVER}" --wait)
  return()
endif()

file(MAKE_DIRECTORY "${LOG_DIR}")
# Wine's background processes inherit stdout and stderr: to files, not to pipes that
# CTest would wait on.
function(run_logged name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_FILE "${LOG_DIR}/${name}.out"
                  ERROR_FILE "${LOG_DIR}/${name}.err")
  if(NOT status EQUAL 0)
    file(READ "${LOG_DIR}/${name}.err" err)
    message(FATAL_ERROR "${ARGN}: status ${status}\n${err}")
  endif()
endfunction()

file(MAKE_DIRECTORY "$ENV{WINEPREFIX}")
execute_process(COMMAND "${WINESERVER}" --kill ERROR_QUIET)  # one left by an interrupted run
execute_process(COMMAND "${WINESERVER}" --wait)
run_logged(server "${WINESERVER}" --persistent)
run_logged(wineboot "${WINE}" wineboot --init)  # makes or updates the prefix
run_logged(warm-up "${WINE}" cmd /c exit 0)
message(STATUS "Wine session up in $ENV{WINEPREFIX}")
