# A Debian package of the installed files (cpack -G DEB in a build folder; tools/package).
# The architecture follows the target: arm64 for the aarch64 preset, amd64 on the host.
# Runtime dependencies are listed by hand because dpkg-shlibdeps cannot read a cross
# sysroot; they are Debian 12's runtime packages of the libraries we link.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME stereoscout)
set(CPACK_PACKAGE_VENDOR "stereoscout")
set(CPACK_PACKAGE_CONTACT "stereoscout maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Stereo-vision SLAM and autonomous exploration for wheeled robots")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(aarch64|arm64)$")
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
else()
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE amd64)
endif()
set(_runtime_depends libopencv-core406 libopencv-imgproc406 libopencv-features2d406 libopencv-flann406
    libgpiod2 libstdc++6 libc6)
if(STEREOSCOUT_HOST_TOOLS)
  list(APPEND _runtime_depends libopencv-imgcodecs406)
endif()
list(JOIN _runtime_depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
include(CPack)
