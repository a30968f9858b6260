# busdecode_fuzz_harness: the fuzz harnesses as a library, shared by the libFuzzer
# targets (fuzz/) and the regression tests (tests/robustness/), so a kept crashing
# input replays through exactly the code that found it. Included by both folders;
# defines the target once.
if(NOT TARGET busdecode_fuzz_harness)
  set(_h ${CMAKE_CURRENT_LIST_DIR})
  add_library(busdecode_fuzz_harness STATIC
    ${_h}/fuzz_harness.cpp ${_h}/reader_harness.cpp ${_h}/decoder_harness.cpp
    ${_h}/rules_harness.cpp ${_h}/vcd_pieces_harness.cpp ${_h}/zip_builder.cpp
    ${_h}/cli_args_harness.cpp ${_h}/formats_harness.cpp ${_h}/declared_fields.cpp)
  target_include_directories(busdecode_fuzz_harness PUBLIC ${_h} ${CMAKE_SOURCE_DIR}/analyzer)
  include(${CMAKE_SOURCE_DIR}/tests/support/feed/direct_feed.cmake)
  target_link_libraries(busdecode_fuzz_harness PUBLIC busdecode_direct_feed)
  target_link_libraries(busdecode_fuzz_harness PUBLIC busdecode_core busdecode_writers)
  foreach(_id spi bissc ssi tmc8100 uart tmcl)
    if(TARGET decoder_${_id})
      string(TOUPPER ${_id} _ID)
      target_link_libraries(busdecode_fuzz_harness PUBLIC decoder_${_id})
      target_compile_definitions(busdecode_fuzz_harness PUBLIC FUZZ_HAVE_${_ID}=1)
    endif()
  endforeach()
  # The rules-file parser depends only on the core and toml++: compiled in directly.
  if(EXISTS ${CMAKE_SOURCE_DIR}/analyzer/verify/rules.cpp)
    target_sources(busdecode_fuzz_harness PRIVATE ${CMAKE_SOURCE_DIR}/analyzer/verify/rules.cpp)
    target_compile_definitions(busdecode_fuzz_harness PUBLIC FUZZ_HAVE_RULES=1)
    if(TARGET tomlplusplus::tomlplusplus)
      target_link_libraries(busdecode_fuzz_harness PRIVATE tomlplusplus::tomlplusplus)
    else()
      target_link_libraries(busdecode_fuzz_harness PRIVATE PkgConfig::TOMLPP)
    endif()
  endif()
endif()
