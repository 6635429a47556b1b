# Install rules and the Debian package (CPack DEB): `cmake --build build --target package` or
# `cpack --config build/CPackConfig.cmake -G DEB`. Layout: programs in /usr/bin, the unit, sysusers, tmpfiles
# and udev entries where Debian 12's systemd and udev read packaged files, examples in
# /usr/share/walkthrough, the kiosk config at /etc/walkthrough/kiosk.toml (a conffile), man pages made by
# help2man from each program's --help. packaging/check-package.sh builds, lists, lints and installs it.
include(GNUInstallDirs)

install(TARGETS walk walkd walk-panel-sim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Debian 12 (before the /usr merge of packaged files) reads units and udev rules from /lib.
install(FILES systemd/walkd.service DESTINATION /lib/systemd/system)
install(FILES systemd/70-walkd.rules DESTINATION /lib/udev/rules.d)
install(FILES systemd/walkd.sysusers DESTINATION lib/sysusers.d RENAME walkd.conf)
install(FILES systemd/walkd.tmpfiles DESTINATION lib/tmpfiles.d RENAME walkd.conf)
install(FILES config/kiosk/hardware.toml DESTINATION /etc/walkthrough RENAME kiosk.toml)
install(DIRECTORY config/kiosk config/scenes config/traces DESTINATION ${CMAKE_INSTALL_DATADIR}/walkthrough)

# Documentation: Debian wants the copyright and a compressed changelog; gzip -n keeps the package
# reproducible (no time stamp in the gzip header).
set(WALK_DOC_DIR ${CMAKE_INSTALL_DATADIR}/doc/walkthrough)
find_program(GZIP_EXECUTABLE gzip REQUIRED)
file(STRINGS packaging/deb/changelog walk_changelog_head LIMIT_COUNT 1)
if(NOT walk_changelog_head MATCHES "^walkthrough \\(${PROJECT_VERSION}\\)")
  message(FATAL_ERROR "packaging/deb/changelog starts with '${walk_changelog_head}': add an entry for "
                      "${PROJECT_VERSION}, the version in CMakeLists.txt")
endif()
set(walk_doc_out ${CMAKE_BINARY_DIR}/packaging)
add_custom_command(OUTPUT ${walk_doc_out}/changelog.gz ${walk_doc_out}/CHANGELOG.md.gz
  COMMAND ${CMAKE_COMMAND} -E make_directory ${walk_doc_out}
  COMMAND ${GZIP_EXECUTABLE} -n -9 -c ${PROJECT_SOURCE_DIR}/packaging/deb/changelog > ${walk_doc_out}/changelog.gz
  COMMAND ${GZIP_EXECUTABLE} -n -9 -c ${PROJECT_SOURCE_DIR}/CHANGELOG.md > ${walk_doc_out}/CHANGELOG.md.gz
  DEPENDS packaging/deb/changelog CHANGELOG.md
  COMMENT "Compressing the changelogs for the package")
set(walk_package_files ${walk_doc_out}/changelog.gz ${walk_doc_out}/CHANGELOG.md.gz)

# Man pages from --help and --version; without help2man (packaging only) the build goes on without them.
find_program(HELP2MAN_EXECUTABLE help2man)
if(HELP2MAN_EXECUTABLE)
  set(walk_man_descriptions
      "walk=display compiler of the Walkthrough building kiosk"
      "walkd=Walkthrough kiosk daemon"
      "walk-panel-sim=simulated Modbus dimmer panel for the Walkthrough kiosk")
  foreach(entry IN LISTS walk_man_descriptions)
    string(REPLACE "=" ";" parts "${entry}")
    list(GET parts 0 program)
    list(GET parts 1 description)
    add_custom_command(OUTPUT ${walk_doc_out}/${program}.1.gz
      COMMAND ${HELP2MAN_EXECUTABLE} --no-info --no-discard-stderr --name=${description}
              --output=${walk_doc_out}/${program}.1 $<TARGET_FILE:${program}>
      COMMAND ${GZIP_EXECUTABLE} -n -9 -f ${walk_doc_out}/${program}.1
      DEPENDS ${program}
      COMMENT "Man page of ${program} (help2man)")
    list(APPEND walk_package_files ${walk_doc_out}/${program}.1.gz)
    install(FILES ${walk_doc_out}/${program}.1.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
  endforeach()
else()
  message(STATUS "help2man not found: no man pages (apt install help2man)")
endif()
add_custom_target(walk_package_files ALL DEPENDS ${walk_package_files})
install(FILES packaging/deb/copyright ${walk_doc_out}/changelog.gz ${walk_doc_out}/CHANGELOG.md.gz
        DESTINATION ${WALK_DOC_DIR})

set(CPACK_PACKAGE_NAME walkthrough)
set(CPACK_PACKAGE_VENDOR "The Walkthrough authors")
set(CPACK_PACKAGE_CONTACT "Walkthrough maintainers <maintainers@users.noreply.h-seed-18005f59.example>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time building walkthrough kiosk and display compiler")
# Debian wants description lines of at most 80 characters.
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "Walkthrough follows the UNC Walkthrough system (Airey, Rohlf and Brooks, 1990).\n"
       "walk compiles a building (DXF, 2D plans, Quake maps, OBJ, glTF) into cells,\n"
       "portals, potentially visible sets and radiosity with one light vector per\n"
       "circuit. walkd runs the kiosk: it draws what the viewer's cell can see while a\n"
       "treadmill, a head tracker and dimmer panels (HID, GPIO, Modbus) drive the walk\n"
       "and the light.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://example.org/walkthrough")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The unit's ExecReload uses /usr/bin/kill; the maintainer scripts use deb-systemd-helper, and adduser where
# systemd-sysusers is missing.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "procps, init-system-helpers (>= 1.52), adduser")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "systemd, udev, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/packaging/deb/postinst ${PROJECT_SOURCE_DIR}/packaging/deb/prerm
    ${PROJECT_SOURCE_DIR}/packaging/deb/postrm ${PROJECT_SOURCE_DIR}/packaging/deb/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_INSTALL_DEFAULT_DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
    WORLD_READ WORLD_EXECUTE)
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
include(CPack)
