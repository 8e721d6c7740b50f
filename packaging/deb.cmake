# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian package, built by CPack inside the build tree:
#   cmake --build build --target package      (or: cd build && cpack -G DEB)
# It depends on Debian's own FreeCAD and installs, under /usr:
#   share/freecad/Mod/HaptiCAD   the workbench with its compiled module (FreeCAD's system Mod folder)
#   bin/hapticad                 the command line
#   lib/udev/rules.d/*.rules     the udev rules for haptic devices, when the tree has them
# These rules belong to the "deb" component and are EXCLUDE_FROM_ALL: a plain
# `cmake --install` (setup.sh, into the user's Mod folder) does not run them.

set(HAPTICAD_DEB_MOD_DIR share/freecad/Mod/HaptiCAD)
install(DIRECTORY ${HAPTICAD_STAGE_DIR}/ DESTINATION ${HAPTICAD_DEB_MOD_DIR} USE_SOURCE_PERMISSIONS
        COMPONENT deb EXCLUDE_FROM_ALL PATTERN "__pycache__" EXCLUDE PATTERN "*.FCStd1" EXCLUDE)

set(HAPTICAD_MOD_PATH /usr/${HAPTICAD_DEB_MOD_DIR})
configure_file(${PROJECT_SOURCE_DIR}/packaging/hapticad.in ${CMAKE_BINARY_DIR}/deb-bin/hapticad @ONLY)
install(PROGRAMS ${CMAKE_BINARY_DIR}/deb-bin/hapticad DESTINATION bin COMPONENT deb EXCLUDE_FROM_ALL)

# udev rules, wherever the devices layer keeps them (packaging/70-hapticad.rules), and a
# postinst that makes the group they name and applies them to plugged-in devices
file(GLOB HAPTICAD_UDEV_RULES ${PROJECT_SOURCE_DIR}/packaging/*.rules ${PROJECT_SOURCE_DIR}/packaging/udev/*.rules
     ${PROJECT_SOURCE_DIR}/devices/udev/*.rules ${PROJECT_SOURCE_DIR}/resources/udev/*.rules)
if(HAPTICAD_UDEV_RULES)
  install(FILES ${HAPTICAD_UDEV_RULES} DESTINATION lib/udev/rules.d COMPONENT deb EXCLUDE_FROM_ALL)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/packaging/deb/postinst)
  set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME hapticad)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "HaptiCAD developers")
set(CPACK_PACKAGE_CONTACT "HaptiCAD developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "FreeCAD workbench to feel CAD parts through a haptic device")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "Tag faces of a FreeCAD part with physical surface properties (material friction and stiffness, "
       "ISO roughness category, anisotropic friction patterns, viscous textures, vibration) and feel them "
       "through a haptic device or a simulated probe. Everything is saved with the .FCStd document.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_COMPONENTS_ALL deb)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# Debian's FreeCAD and the Python modules the workbench imports; shared libraries the
# compiled module links (hidapi, ...) are added by dpkg-shlibdeps
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "freecad (>= 0.20), python3-numpy, python3-matplotlib, python3-pivy, python3-pyside2.qtwidgets")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_STRIP_FILES ON)  # the compiled module without its debug information
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
include(CPack)
