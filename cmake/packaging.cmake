# packaging — one Debian package `cubdance` per architecture, made by CPack
# from the install() rules (app/cubdance, board): amd64 from a host build,
# arm64 from the cross build (cmake/aarch64-linux-gnu.cmake). A package
# comes from a build configured with -DCUB_PACKAGE=ON (the binary then looks
# for its assets in /usr/share/cubdance) and without sanitizers;
# scripts/test.sh makes both, tests/package checks them.
if(CUB_FUZZ)
  return()
endif()
option(CUB_PACKAGE "Build to be installed: the default asset paths point at <prefix>/share/cubdance" OFF)
# A package installs under /usr (the unit runs /usr/bin/cubdance-pi), and the
# binary's compiled-in asset paths come from the same prefix.
if(CUB_PACKAGE AND CMAKE_INSTALL_PREFIX_INITIALIZED_TO_DEFAULT)
  set(CMAKE_INSTALL_PREFIX "/usr" CACHE PATH "Install prefix" FORCE)
endif()
include(GNUInstallDirs)

# Where the system files go. Debian 12 still ships units and udev rules
# under /lib (merged /usr makes it the same place as /usr/lib, but dpkg
# tracks the path as written, so packages keep /lib until Debian moves).
set(CUB_SYSTEMD_UNIT_DIR "/lib/systemd/system" CACHE PATH "Where the systemd unit is installed")
set(CUB_UDEV_RULES_DIR "/lib/udev/rules.d" CACHE PATH "Where the udev rules are installed")
set(CUB_SYSUSERS_DIR "/usr/lib/sysusers.d" CACHE PATH "Where the sysusers.d file is installed")
set(CUB_CONFIG_DIR "/etc/cubdance" CACHE PATH "Where the box's config file is installed")

if(CUB_PACKAGE AND NOT CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  message(WARNING "CUB_PACKAGE with CMAKE_INSTALL_PREFIX=${CMAKE_INSTALL_PREFIX}: the package "
                  "installs under /usr, the binary looks for its assets elsewhere")
endif()
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_PACKAGE_NAME "cubdance")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_CONTACT "the cubdance developers <cubdance@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "dancing-bear coach for children on a TV, with a Kinect")
set(CPACK_PACKAGE_DESCRIPTION
    "A toy-bear coach on the TV teaches a child a dance to a song and, watching\n\
through a Kinect v1, corrects a wrong move at once. START and STOP buttons on\n\
GPIO; no network. Starts at boot as the systemd service cubdance.")
set(CPACK_DEBIAN_FILE_NAME "DEB-DEFAULT") # cubdance_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION "games")
set(CPACK_DEBIAN_PACKAGE_PRIORITY "optional")
set(CPACK_STRIP_FILES ON)

# Architecture from the target, not from the machine that builds.
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(aarch64|arm64)$")
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "arm64")
elseif(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "amd64")
else()
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "${CMAKE_SYSTEM_PROCESSOR}")
endif()

# Library dependencies from dpkg-shlibdeps, which reads the binaries' ELF
# NEEDED entries and the arch's dpkg database (with the arm64 -dev packages
# installed through multiarch, the cross build finds its :arm64 libraries
# the same way). What no ELF file says: the SoundFont the songs play with
# (CUB_MUSIC_SOUNDFONT), Mesa's EGL/GLES drivers (libegl1 only loads them),
# and systemd (sysusers, the unit).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "timgm6mb-soundfont, fonts-dejavu-core, libegl-mesa0, libgl1-mesa-dri, systemd")

# The config is the admin's: dpkg keeps their edits over an upgrade.
# postinst makes the service user (sysusers.d) and enables the unit.
set(CUB_PACKAGE_CONTROL_DIR "${CMAKE_BINARY_DIR}/package-control")
file(WRITE "${CUB_PACKAGE_CONTROL_DIR}/conffiles" "${CUB_CONFIG_DIR}/cubdance.conf\n")
foreach(script postinst prerm postrm)
  file(COPY "${CMAKE_SOURCE_DIR}/board/pi/debian/${script}" DESTINATION "${CUB_PACKAGE_CONTROL_DIR}"
       FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                        WORLD_READ WORLD_EXECUTE)
endforeach()
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    "${CUB_PACKAGE_CONTROL_DIR}/conffiles;${CUB_PACKAGE_CONTROL_DIR}/postinst;\
${CUB_PACKAGE_CONTROL_DIR}/prerm;${CUB_PACKAGE_CONTROL_DIR}/postrm")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

# cpack installs what is built; it does not build everything first (the
# package needs the box program, not cubtool and the test suite).
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
set(CPACK_SOURCE_GENERATOR "")
include(CPack)
