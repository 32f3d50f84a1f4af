# Finds the OpenCV modules stereoscout is allowed to use, one imported target each
# (OpenCV::core, OpenCV::imgproc, ...). Debian ships OpenCVConfig.cmake only in the
# libopencv-dev metapackage, which drags in calib3d, dnn, VTK and MPI; the per-module
# -dev packages we install carry headers and libraries but no CMake config, so we look
# them up directly. Works the same against a cross sysroot (CMAKE_SYSROOT).
set(_required_vars)
find_path(OpenCVComponents_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
list(APPEND _required_vars OpenCVComponents_INCLUDE_DIR)
foreach(_component IN LISTS OpenCVComponents_FIND_COMPONENTS)
  find_library(OpenCVComponents_${_component}_LIBRARY NAMES opencv_${_component})
  if(OpenCVComponents_${_component}_LIBRARY AND OpenCVComponents_INCLUDE_DIR)
    set(OpenCVComponents_${_component}_FOUND TRUE)
    if(NOT TARGET OpenCV::${_component})
      add_library(OpenCV::${_component} UNKNOWN IMPORTED)
      set_target_properties(OpenCV::${_component} PROPERTIES
        IMPORTED_LOCATION "${OpenCVComponents_${_component}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${OpenCVComponents_INCLUDE_DIR}")
    endif()
  else()
    set(OpenCVComponents_${_component}_FOUND FALSE)
  endif()
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenCVComponents
  REQUIRED_VARS ${_required_vars}
  HANDLE_COMPONENTS
  REASON_FAILURE_MESSAGE "install the Debian packages libopencv-<component>-dev (tools/setup does)")
