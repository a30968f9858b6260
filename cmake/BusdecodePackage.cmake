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
# Debian 12's packages of the libraries the binaries, plugins and Python module load (their
# NEEDED entries), at the versions dpkg-shlibdeps gives for them; written out, so that a
# machine without dpkg-dev makes the same package.
string(CONCAT CPACK_DEBIAN_PACKAGE_DEPENDS
    "libc6 (>= 2.34), libstdc++6 (>= 12), libgcc-s1 (>= 7), libqt6core6 (>= 6.4.0), "
    "libfmt9 (>= 9.1.0+ds1), libzip4 (>= 1.7.0), liblcm1, libtomlplusplus3 (>= 3.2.0), "
    "zlib1g (>= 1:1.2.0), liblzma5 (>= 5.1.1alpha+20120614), libzstd1 (>= 1.5.2)")
get_property(_live GLOBAL PROPERTY BUSDECODE_LIVE)
if(_live)  # decode --device (analyzer/CMakeLists.txt)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS
         ", libsigrok4 (>= 0.5.2), libglib2.0-0 (>= 2.28.0)")
endif()
get_property(_python GLOBAL PROPERTY BUSDECODE_PYTHON_VERSION)
if(_python)  # the module is built for one CPython 3.N (python/CMakeLists.txt)
  string(REGEX REPLACE "^3\\." "" _minor "${_python}")
  math(EXPR _next "${_minor} + 1")
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", python3 (>= ${_python}), python3 (<< 3.${_next})")
endif()
include(CPack)
