# busdecode_fstapi: GTKWave's FST library (fstapi.c, fastlz.c, lz4.c; MIT) built as a small
# static library from the sources Debian's `verilator` package ships, never copied into
# the tree. Its fatal errors (exit(255)) and messages are redirected by
# analyzer/capture/fst_api_shim.h, so that a broken file is one InputError, not an exit.
set(BUSDECODE_FSTAPI_DIR "/usr/share/verilator/include/gtkwave" CACHE PATH
    "Folder holding fstapi.c, fastlz.c and lz4.c (Debian: package verilator)")
foreach(_f fstapi.c fstapi.h fastlz.c lz4.c fst_config.h)
  if(NOT EXISTS "${BUSDECODE_FSTAPI_DIR}/${_f}")
    message(FATAL_ERROR "FST support needs fstapi's sources: ${BUSDECODE_FSTAPI_DIR}/${_f} "
                        "is missing (install Debian's `verilator` package, or set "
                        "-DBUSDECODE_FSTAPI_DIR to a folder holding fstapi.c, fastlz.c, lz4.c)")
  endif()
endforeach()
enable_language(C)
pkg_check_modules(FSTAPI_ZLIB REQUIRED IMPORTED_TARGET zlib)
add_library(busdecode_fstapi STATIC ${BUSDECODE_FSTAPI_DIR}/fstapi.c
            ${BUSDECODE_FSTAPI_DIR}/fastlz.c ${BUSDECODE_FSTAPI_DIR}/lz4.c)
target_include_directories(busdecode_fstapi SYSTEM PUBLIC ${BUSDECODE_FSTAPI_DIR})
target_compile_definitions(busdecode_fstapi PRIVATE FST_CONFIG_INCLUDE="fst_config.h")
# -fexceptions: the shim's exit() throws a C++ exception through fstapi's frames.
target_compile_options(busdecode_fstapi PRIVATE -w -fexceptions -include
                       ${CMAKE_SOURCE_DIR}/analyzer/capture/fst_api_shim.h)
# fstapi stores 32- and 64-bit words at unaligned addresses (fine on x86, its target);
# the sanitizer build checks everything else of it.
if(BUSDECODE_SANITIZE)
  target_compile_options(busdecode_fstapi PRIVATE -fno-sanitize=alignment)
endif()
set_target_properties(busdecode_fstapi PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(busdecode_fstapi PUBLIC PkgConfig::FSTAPI_ZLIB)
