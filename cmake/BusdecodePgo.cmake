# Profile-guided optimisation (GCC) of the code that decodes: the core library and the
# decoders. Side by side on the 500 MB captures, read back, it took SPI's `decode` from
# 265 to 247 ms and BiSS-C's from 453 to 406 ms (bench/README.md, "Profile-guided
# optimisation", with the command).
#
# How the build does it, with nothing to do by hand:
#  1. build/pgo/build is a second build of this source tree (ExternalProject), with the
#     core and the decoders instrumented (-fprofile-generate). It builds only `decode`,
#     the SPI and BiSS-C plugins and bench/'s `make_capture` (whatever BUSDECODE_BENCH
#     says here).
#  2. cmake/pgo_train.sh runs that `decode` on SPI and BiSS-C VCD captures written by
#     `make_capture` (times of up to 8, 9 and 10 digits; text and JSONL output, one and
#     two threads): the counts land in build/pgo/profile, and build/pgo/profile.stamp
#     marks them done.
#  3. The core's and the decoders' objects in this build depend on that stamp and compile
#     with -fprofile-use. Decoders the training does not run keep -O3's code
#     (-fprofile-partial-training).
# Any change to the instrumented code retrains and so recompiles the core and the
# decoders here: configure with -DBUSDECODE_PGO=OFF for quick edit-build cycles.
# -fprofile-prefix-path makes the profiles' names relative to each build's own folder,
# so that the second build's counts are found for this build's objects.

# On by default in GCC's optimised builds that build the two decoders it trains on.
set(_pgo_default OFF)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo)$"
   AND NOT BUSDECODE_SANITIZE AND NOT BUSDECODE_FUZZ
   AND (NOT BUSDECODE_DECODERS OR ("spi" IN_LIST BUSDECODE_DECODERS
                                    AND "bissc" IN_LIST BUSDECODE_DECODERS)))
  set(_pgo_default ON)
endif()
option(BUSDECODE_PGO "Profile-guided optimisation of the core and the decoders (GCC)"
       ${_pgo_default})
# Set by step 1 in its own build only: GENERATE instruments instead.
set(BUSDECODE_PGO_STAGE "" CACHE STRING "internal: GENERATE in the profiling build")
set(BUSDECODE_PGO_PROFILE_DIR "" CACHE PATH "internal: where the profiling build writes")
mark_as_advanced(BUSDECODE_PGO_STAGE BUSDECODE_PGO_PROFILE_DIR)

set(BUSDECODE_PGO_OPTIONS "")
if(BUSDECODE_PGO_STAGE STREQUAL "GENERATE")
  # Atomic counters: decode's two threads run the same code.
  set(BUSDECODE_PGO_OPTIONS -fprofile-generate=${BUSDECODE_PGO_PROFILE_DIR}
      -fprofile-prefix-path=${CMAKE_BINARY_DIR} -fprofile-update=atomic)
  add_link_options(-fprofile-generate)
elseif(BUSDECODE_PGO)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    message(FATAL_ERROR "BUSDECODE_PGO needs GCC (configure with -DBUSDECODE_PGO=OFF)")
  endif()
  set(_pgo_root ${CMAKE_BINARY_DIR}/pgo)
  set(BUSDECODE_PGO_STAMP ${_pgo_root}/profile.stamp)
  set(BUSDECODE_PGO_OPTIONS -fprofile-use=${_pgo_root}/profile
      -fprofile-prefix-path=${CMAKE_BINARY_DIR} -fprofile-partial-training
      -Wno-missing-profile)
endif()

# The core's and the decoders' speed options: -O3 (CMakeLists.txt) and the profile.
function(busdecode_speed target)
  target_compile_options(${target} PRIVATE ${BUSDECODE_SPEED_OPTIONS} ${BUSDECODE_PGO_OPTIONS})
  set_property(GLOBAL APPEND PROPERTY BUSDECODE_PGO_TARGETS ${target})
endfunction()

# Steps 1 and 2, and the objects' dependence on them; called once every target exists.
function(busdecode_pgo_finish)
  if(NOT BUSDECODE_PGO OR BUSDECODE_PGO_STAGE STREQUAL "GENERATE")
    return()
  endif()
  if(NOT TARGET busdecode_spi OR NOT TARGET busdecode_bissc)
    message(FATAL_ERROR "BUSDECODE_PGO trains on the SPI and BiSS-C decoders: build them "
                        "(BUSDECODE_DECODERS), or configure with -DBUSDECODE_PGO=OFF")
  endif()
  set(_root ${CMAKE_BINARY_DIR}/pgo)
  set(_bin ${_root}/build)
  set(_products ${_bin}/bin/decode ${_bin}/bin/make_capture ${_bin}/lib/libbusdecode_core.so
                ${_bin}/bin/plugins/busdecode_spi.so ${_bin}/bin/plugins/busdecode_bissc.so)
  string(REPLACE ";" "|" _decoders "${BUSDECODE_DECODERS}")
  # The same flags as this build, or the counts would not fit its code (GCC stops the
  # build on a profile that does not match), less -g: debugging information changes no
  # code and takes about a fifth of the compiling.
  string(TOUPPER "${CMAKE_BUILD_TYPE}" _config)
  string(REGEX REPLACE "(^| )-g[0-9]*" "" _config_flags "${CMAKE_CXX_FLAGS_${_config}}")
  include(ExternalProject)
  # BUILD_ALWAYS: the inner ninja decides what is out of date; the products' times (restat)
  # decide whether to train again.
  ExternalProject_Add(busdecode_pgo_build
    SOURCE_DIR ${PROJECT_SOURCE_DIR}
    BINARY_DIR ${_bin}
    PREFIX ${_root}/ep
    LIST_SEPARATOR |
    CMAKE_ARGS -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}
               -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
               "-DCMAKE_CXX_FLAGS=${CMAKE_CXX_FLAGS}"
               "-DCMAKE_CXX_FLAGS_${_config}=${_config_flags}"
               -DBUSDECODE_PGO=OFF -DBUSDECODE_PGO_STAGE=GENERATE
               -DBUSDECODE_PGO_PROFILE_DIR=${_root}/profile
               -DBUSDECODE_BENCH=ON -DBUSDECODE_DECODERS=${_decoders}
    BUILD_COMMAND ${CMAKE_COMMAND} --build <BINARY_DIR> --target decode make_capture
                  busdecode_spi busdecode_bissc
    INSTALL_COMMAND ""
    BUILD_ALWAYS ON
    BUILD_BYPRODUCTS ${_products})
  add_custom_command(OUTPUT ${BUSDECODE_PGO_STAMP}
    COMMAND bash ${PROJECT_SOURCE_DIR}/cmake/pgo_train.sh ${_bin}/bin ${_root}/profile
            ${_root}/train ${BUSDECODE_PGO_STAMP}
    DEPENDS busdecode_pgo_build ${_products} ${PROJECT_SOURCE_DIR}/cmake/pgo_train.sh
    COMMENT "Training the profile for -fprofile-use (cmake/pgo_train.sh)")
  add_custom_target(busdecode_pgo_profile DEPENDS ${BUSDECODE_PGO_STAMP})
  get_property(_targets GLOBAL PROPERTY BUSDECODE_PGO_TARGETS)
  foreach(_t ${_targets})
    add_dependencies(${_t} busdecode_pgo_profile)
    get_target_property(_sources ${_t} SOURCES)
    get_target_property(_dir ${_t} SOURCE_DIR)
    list(TRANSFORM _sources REPLACE "^([^/])" "${_dir}/\\1")
    # A new profile recompiles the objects it is for.
    set_source_files_properties(${_sources} TARGET_DIRECTORY ${_t}
      PROPERTIES OBJECT_DEPENDS ${BUSDECODE_PGO_STAMP})
  endforeach()
endfunction()
