# Cross-compiling for 64-bit ARM onboard computers (Debian 12 arm64) with Debian's cross
# compiler (package g++-aarch64-linux-gnu) against a sysroot made by
# tools/make-sysroot-aarch64. Pass the sysroot as STEREOSCOUT_SYSROOT (the aarch64 preset and
# `tools/test --target aarch64` do); tests run under qemu-aarch64 user-mode emulation.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

if(NOT STEREOSCOUT_SYSROOT)
  set(STEREOSCOUT_SYSROOT "$ENV{STEREOSCOUT_SYSROOT}")
endif()
if(NOT STEREOSCOUT_SYSROOT OR NOT EXISTS "${STEREOSCOUT_SYSROOT}/usr/include")
  message(FATAL_ERROR "aarch64 toolchain: set STEREOSCOUT_SYSROOT to a sysroot made by "
                      "tools/make-sysroot-aarch64 (got '${STEREOSCOUT_SYSROOT}')")
endif()
# try_compile projects do not see cache variables unless told to pass them on.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES STEREOSCOUT_SYSROOT)

set(CMAKE_SYSROOT "${STEREOSCOUT_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH "${STEREOSCOUT_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# Shared libraries in the sysroot name their dependencies by soname; let the linker find
# them there, and run test programs (gtest discovery, ctest) under qemu with that root.
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${STEREOSCOUT_SYSROOT}/usr/lib/aarch64-linux-gnu -Wl,-rpath-link,${STEREOSCOUT_SYSROOT}/usr/lib/aarch64-linux-gnu/blas -Wl,-rpath-link,${STEREOSCOUT_SYSROOT}/usr/lib/aarch64-linux-gnu/lapack")
find_program(STEREOSCOUT_QEMU_AARCH64 qemu-aarch64)
if(STEREOSCOUT_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${STEREOSCOUT_QEMU_AARCH64};-L;${STEREOSCOUT_SYSROOT}")
endif()
