# Cross build for 64-bit Windows with MinGW-w64 (Debian: g++-mingw-w64-x86-64), tests run
# under Wine (Debian: wine, wine64). Used by the `mingw` preset:
#   cmake --workflow --preset mingw
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(RAYTRACER_MINGW_TRIPLET x86_64-w64-mingw32)

set(CMAKE_FIND_ROOT_PATH /usr/${RAYTRACER_MINGW_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The posix threading flavour: it supports std::thread (with GCC 12, the win32 flavour does
# not), and -static below links its winpthread runtime into the executable.
find_program(RAYTRACER_MINGW_CXX NAMES ${RAYTRACER_MINGW_TRIPLET}-g++-posix ${RAYTRACER_MINGW_TRIPLET}-g++
             REQUIRED)
set(CMAKE_CXX_COMPILER "${RAYTRACER_MINGW_CXX}")
set(CMAKE_RC_COMPILER ${RAYTRACER_MINGW_TRIPLET}-windres)

# Self-contained .exe files: libstdc++, libgcc and winpthread linked in, so neither Wine
# nor a grader's Windows machine needs the MinGW DLLs.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")

# CTest runs the Windows test executables under Wine, which they in turn use to start
# raytracer.exe (through cmd.exe, as on Windows).
find_program(RAYTRACER_WINE NAMES wine wine64)
if(RAYTRACER_WINE)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${RAYTRACER_WINE}")
endif()
