# Installing and packaging. `cmake --install` puts the programs and their files
# where Debian expects them; `cpack -G DEB` (scripts/package) makes of that one
# package, rcm-gcs_VERSION_ARCH.deb, and scripts/try-package installs it and
# runs what it installed. Included by the top CMakeLists.txt after the
# programs are defined.

# The console's name to the desktop: its menu entry, icons, AppStream
# metadata and Wayland app_id. AppStream wants it in reverse-DNS form.
set(RCM_APP_ID "org.rcm_gcs.gcs")
target_compile_definitions(gcs PRIVATE RCM_APP_ID="${RCM_APP_ID}")


# Programs and their data side by side, bin/ and share/rcm-gcs/, as
# link/session/DataFolder.h looks for them (fixed here, not left to
# GNUInstallDirs, so that the two cannot part). The build tree has the same
# shape: build/share/rcm-gcs is a link to the sources' resources/.
set(RCM_DATA_DESTINATION share/rcm-gcs)
set(RCM_DOC_DESTINATION share/doc/rcm-gcs)
file(MAKE_DIRECTORY ${CMAKE_RUNTIME_OUTPUT_DIRECTORY}/../share)
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/resources ${CMAKE_RUNTIME_OUTPUT_DIRECTORY}/../share/rcm-gcs SYMBOLIC)

# Debian's Wireshark loads Lua plugins from lib/<multiarch>/wireshark/plugins
# (`tshark -G folders`: "Global Lua Plugins"; the versioned plugins/4.0 below
# it is for compiled plugins).
if(CMAKE_LIBRARY_ARCHITECTURE)
  set(RCM_WIRESHARK_DESTINATION lib/${CMAKE_LIBRARY_ARCHITECTURE}/wireshark/plugins)
else()
  set(RCM_WIRESHARK_DESTINATION lib/wireshark/plugins)
endif()

# Who answers for the package: the address the project commits under.
set(RCM_MAINTAINER "rcm-gcs maintainers <maintainers@users.noreply.h-seed-c3956437.example>")

# The package installs under /usr; its man pages name the paths there.
set(RCM_PACKAGE_PREFIX /usr)
set(RCM_PACKAGE_DATA_DIR ${RCM_PACKAGE_PREFIX}/${RCM_DATA_DESTINATION})
set(RCM_PACKAGE_DOC_DIR ${RCM_PACKAGE_PREFIX}/${RCM_DOC_DESTINATION})
set(RCM_PACKAGE_WIRESHARK_DIR ${RCM_PACKAGE_PREFIX}/${RCM_WIRESHARK_DESTINATION})
set(RCM_PACKAGING_DIR ${CMAKE_BINARY_DIR}/packaging)

install(TARGETS gcs rcm uasim satmodem RUNTIME DESTINATION bin)
# Airframes and the alarm tone are built into the programs too; these copies
# are for reading and for making one's own.
install(DIRECTORY resources/airframes resources/plans resources/samples resources/scenarios resources/sounds
                  resources/voice
        DESTINATION ${RCM_DATA_DESTINATION} PATTERN "*.qrc" EXCLUDE)
# The checked-in copy: tst_dissector and tst_rcm keep it equal to `rcm dissector`.
install(FILES resources/wireshark/rcm.lua DESTINATION ${RCM_WIRESHARK_DESTINATION})

# The menu entry, its icons, and what software centres show.
execute_process(COMMAND git -C ${PROJECT_SOURCE_DIR} log -1 --format=%cs
                OUTPUT_VARIABLE RCM_RELEASE_DATE OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git -C ${PROJECT_SOURCE_DIR} log -1 --format=%cD
                OUTPUT_VARIABLE RCM_RELEASE_TIME OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT RCM_RELEASE_DATE OR NOT RCM_RELEASE_TIME)  # not a git clone: today (or SOURCE_DATE_EPOCH)
  string(TIMESTAMP RCM_RELEASE_DATE "%Y-%m-%d" UTC)
  string(TIMESTAMP RCM_RELEASE_TIME "%a, %d %b %Y %H:%M:%S +0000" UTC)
endif()
configure_file(resources/desktop/gcs.desktop.in ${RCM_PACKAGING_DIR}/${RCM_APP_ID}.desktop @ONLY)
configure_file(resources/desktop/gcs.metainfo.xml.in ${RCM_PACKAGING_DIR}/${RCM_APP_ID}.metainfo.xml @ONLY)
install(FILES ${RCM_PACKAGING_DIR}/${RCM_APP_ID}.desktop DESTINATION share/applications)
install(FILES ${RCM_PACKAGING_DIR}/${RCM_APP_ID}.metainfo.xml DESTINATION share/metainfo)
foreach(size 16 24 32 48 64 128 256)
  install(FILES resources/desktop/icons/gcs-${size}.png DESTINATION share/icons/hicolor/${size}x${size}/apps
          RENAME ${RCM_APP_ID}.png)
endforeach()
install(FILES resources/desktop/icons/gcs.svg DESTINATION share/icons/hicolor/scalable/apps
        RENAME ${RCM_APP_ID}.svg)

# Man pages from each program's --help (so they say what the program says),
# with the hand-written sections of docs/man/PROGRAM.h2m: help2man for the Qt
# programs, cmake/rcm-help-to-man.pl for rcm's own layout. Built with `all`.
find_program(RCM_HELP2MAN help2man)
find_program(RCM_GZIP gzip)
find_program(RCM_PERL perl)
set(RCM_MAN_gcs "operator console of the RCM ground control station")
set(RCM_MAN_uasim "simulated aircraft for rehearsals of the RCM ground control station")
set(RCM_MAN_satmodem "model of a pair of satellite phone modems on pseudo-terminals")
set(RCM_MAN_rcm "Remote Control Messages between the text format and frames")
set(RCM_MAN_DIR ${CMAKE_BINARY_DIR}/man)
set(RCM_MAN_PAGES)
if(RCM_HELP2MAN AND RCM_GZIP AND RCM_PERL)
  foreach(program gcs uasim satmodem rcm)
    configure_file(docs/man/${program}.h2m ${RCM_MAN_DIR}/${program}.h2m @ONLY)
    set(page ${RCM_MAN_DIR}/${program}.1)
    if(program STREQUAL "rcm")
      set(make_page ${RCM_PERL} ${PROJECT_SOURCE_DIR}/cmake/rcm-help-to-man.pl $<TARGET_FILE:rcm> ${RCM_MAN_${program}}
                    ${PROJECT_VERSION} ${RCM_MAN_DIR}/${program}.h2m ${page})
    else()
      # gcs needs a display to start, even for --help.
      set(make_page ${CMAKE_COMMAND} -E env QT_QPA_PLATFORM=offscreen ${RCM_HELP2MAN} --no-info
                    --version-string=${PROJECT_VERSION} --name=${RCM_MAN_${program}}
                    --include=${RCM_MAN_DIR}/${program}.h2m --output=${page} $<TARGET_FILE:${program}>)
    endif()
    add_custom_command(OUTPUT ${page}.gz
                       COMMAND ${make_page}
                       COMMAND ${RCM_GZIP} -9nf ${page}
                       DEPENDS ${program} ${RCM_MAN_DIR}/${program}.h2m cmake/rcm-help-to-man.pl
                       COMMENT "Man page of ${program}"
                       VERBATIM)
    list(APPEND RCM_MAN_PAGES ${page}.gz)
  endforeach()
  add_custom_target(manpages ALL DEPENDS ${RCM_MAN_PAGES})
  install(FILES ${RCM_MAN_PAGES} DESTINATION share/man/man1)
else()
  message(STATUS "No man pages: help2man, gzip or perl not found (scripts/install-deps installs them)")
endif()

# What Debian wants beside every package: its copyright and a changelog.
# Debian's changelog format; the project's history is its git log.
configure_file(cmake/debian/changelog.in ${RCM_PACKAGING_DIR}/changelog @ONLY)
if(RCM_GZIP)
  add_custom_command(OUTPUT ${RCM_PACKAGING_DIR}/changelog.gz
                     COMMAND ${RCM_GZIP} -9nc ${RCM_PACKAGING_DIR}/changelog > ${RCM_PACKAGING_DIR}/changelog.gz
                     DEPENDS ${RCM_PACKAGING_DIR}/changelog)
  add_custom_target(package_changelog ALL DEPENDS ${RCM_PACKAGING_DIR}/changelog.gz)
  install(FILES ${RCM_PACKAGING_DIR}/changelog.gz DESTINATION ${RCM_DOC_DESTINATION})
endif()
file(GLOB RCM_DOCS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md)
install(FILES cmake/debian/copyright README.md ${RCM_DOCS} DESTINATION ${RCM_DOC_DESTINATION})

# The package.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rcm-gcs)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "The rcm-gcs developers")
set(CPACK_PACKAGE_CONTACT ${RCM_MAINTAINER})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "ground control station for aircraft commanded by Remote Control Message")
set(CPACK_PACKAGE_DESCRIPTION
    "An operator console for unmanned aircraft commanded with the Remote Control
Message: a 600-byte frame protected by Reed-Solomon RS(255,223), sent once a
second over a satellite phone's modem or as a UDP datagram. Panels for
engines, flaps, landing gear, lights, fuel dump, radios and cameras; frame
logs that Wireshark reads; flight plans on an offline map; authenticated and
enciphered links; backup stations and observers over an MQTT broker.

Also rcm (messages between text and frames), uasim (a simulated aircraft),
satmodem (a pair of satellite modems on pseudo-terminals), rehearsal
scenarios, and a Wireshark dissector.")
set(CPACK_PACKAGING_INSTALL_PREFIX ${RCM_PACKAGE_PREFIX})
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR})
set(CPACK_STRIP_FILES TRUE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Libraries from what the programs link (dpkg-shlibdeps); plugins Qt loads
# at run time are not linked, so named: SQLite for MBTiles map files.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libqt6sql6-sqlite")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "mosquitto, tshark | wireshark")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
set(CPACK_SOURCE_GENERATOR TXZ)
set(CPACK_SOURCE_IGNORE_FILES "/\\\\.git/" "/build[^/]*/")
include(CPack)
