# find_package(OpenCV COMPONENTS core imgproc ...) for Debian's per-module packages. OpenCVConfig.cmake ships
# only with libopencv-dev, which pulls in every OpenCV module (GUI, video, contrib); scripts/setup.sh installs
# just libopencv-{core,imgproc,imgcodecs}-dev, which carry headers and libraries but no CMake package. So:
# use the config package when it exists, otherwise find each requested module's library and the opencv4
# headers and define the same imported targets (opencv_core, ...) and OpenCV_LIBS / OpenCV_INCLUDE_DIRS.
find_package(OpenCV CONFIG QUIET COMPONENTS ${OpenCV_FIND_COMPONENTS})
if(OpenCV_FOUND)
  return()
endif()

find_path(OpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_cmt_opencv_required OpenCV_INCLUDE_DIR)
set(OpenCV_LIBS)
foreach(_module IN LISTS OpenCV_FIND_COMPONENTS)
  find_library(OpenCV_${_module}_LIBRARY opencv_${_module})
  list(APPEND _cmt_opencv_required OpenCV_${_module}_LIBRARY)
  if(OpenCV_${_module}_LIBRARY AND NOT TARGET opencv_${_module})
    add_library(opencv_${_module} UNKNOWN IMPORTED)
    set_target_properties(opencv_${_module} PROPERTIES
      IMPORTED_LOCATION "${OpenCV_${_module}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${OpenCV_INCLUDE_DIR}")
  endif()
  list(APPEND OpenCV_LIBS opencv_${_module})
endforeach()
set(OpenCV_INCLUDE_DIRS "${OpenCV_INCLUDE_DIR}")

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenCV REQUIRED_VARS ${_cmt_opencv_required})
