# Installing beside the binaries' own rules: the documents and example captures, then
# CPack, so that `cpack -G DEB` in the build directory makes a Debian package of decode,
# decode-monitor, the plugins, the core library and headers, the LCM types and the docs.
# The package installs under /usr; every binary finds lib/ and lib/busdecode/plugins
# relative to itself, so its tree also works extracted anywhere (`dpkg-deb -x`).
install(FILES ${CMAKE_SOURCE_DIR}/README.md ${CMAKE_SOURCE_DIR}/THIRD-PARTY.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${CMAKE_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
# Debian looks for the licence under this name.
install(FILES ${CMAKE_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/captures/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)

set(CPACK_PACKAGE_NAME busdecode)
set(CPACK_PACKAGE_VENDOR "The busdecode authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "protocol analyser for SSI, BiSS-C, TMC8100 SPI, TMCL, SPI and UART captures")
set(CPACK_PACKAGE_DESCRIPTION
    "decode reads logic-analyser captures (VCD, CSV, sigrok .sr) in constant memory and prints every frame with its CRC and timing as text or JSON lines, verifies batches against rules, writes reports and publishes events over LCM.")
set(CPACK_PACKAGE_CONTACT "The busdecode authors <busdecode@users.noreply.github.com>")
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION electronics)
# The run-time libraries of Debian 12 that `ldd build/bin/decode` names (toml++ is
# header-only on some systems, a library on Debian).
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libc6, libstdc++6, libqt6core6, libfmt9, libzip4, liblcm1, libtomlplusplus3")
get_property(_live GLOBAL PROPERTY BUSDECODE_LIVE)
if(_live)  # decode --device (analyzer/CMakeLists.txt)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libsigrok4")
endif()
include(CPack)
