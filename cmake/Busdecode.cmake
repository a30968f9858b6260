# Helpers shared by every decoder and test folder, so each folder's CMakeLists.txt is a
# few declarative lines.

include(${CMAKE_SOURCE_DIR}/decoders/kit/kit.cmake)

# busdecode_decoder(ID <id> FACTORY <function> SOURCES <files...> [LIBS <targets...>]
#                   [PROVIDES <decoder ids...>] [EXAMPLES <files...>])
#   Builds decoder_<id> (static, PIC: linked by tests and other decoders) and the Qt
#   plugin busdecode_<id> in build/bin/plugins. FACTORY names a function
#   `std::shared_ptr<const busdecode::DecoderFactory> FACTORY()` (namespace busdecode)
#   defined in SOURCES; the plugin source is generated from one template. PROVIDES lists
#   the ids of the decoders its factories make (default: <id>), for the plugin's
#   metadata: a run loads only the plugins that provide what it asks for (a wrong list
#   costs time, not results: the CLI loads every plugin before it gives up on an id).
#   EXAMPLES (<id>_examples.cpp) builds examples_<id>: the decoder's example captures
#   in the kit's shape (decoders/kit), for make_examples and the decoder's tests.
function(busdecode_decoder)
  cmake_parse_arguments(D "" "ID" "FACTORY;SOURCES;LIBS;PROVIDES;EXAMPLES" ${ARGN})
  add_library(decoder_${D_ID} STATIC ${D_SOURCES})
  busdecode_speed(decoder_${D_ID})  # -O3 and the profile (cmake/BusdecodePgo.cmake)
  target_include_directories(decoder_${D_ID} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(decoder_${D_ID} PUBLIC busdecode_core ${D_LIBS})
  if(D_EXAMPLES)
    add_library(examples_${D_ID} OBJECT ${D_EXAMPLES})  # whole: each lists itself
    target_link_libraries(examples_${D_ID} PUBLIC decoder_${D_ID} busdecode_examples)
  endif()

  set(PLUGIN_CLASS "BusdecodePlugin_${D_ID}")
  set(PLUGIN_ID "${D_ID}")
  set(_decls "")
  set(_calls "")
  foreach(_f ${D_FACTORY})
    string(APPEND _decls "std::shared_ptr<const DecoderFactory> ${_f}();\n")
    string(APPEND _calls "        out.push_back(busdecode::${_f}());\n")
  endforeach()
  set(PLUGIN_FACTORY_DECLS "${_decls}")
  set(PLUGIN_FACTORY_CALLS "${_calls}")
  if(NOT D_PROVIDES)
    set(D_PROVIDES ${D_ID})
  endif()
  list(TRANSFORM D_PROVIDES PREPEND "\"")
  list(TRANSFORM D_PROVIDES APPEND "\"")
  list(JOIN D_PROVIDES ", " _ids)
  file(CONFIGURE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${D_ID}_plugin.json
       CONTENT "{ \"decoders\": [@_ids@] }\n" @ONLY)
  configure_file(${CMAKE_SOURCE_DIR}/plugins/plugin_template.cpp.in
                 ${CMAKE_CURRENT_BINARY_DIR}/${D_ID}_plugin.cpp @ONLY)
  add_library(busdecode_${D_ID} MODULE ${CMAKE_CURRENT_BINARY_DIR}/${D_ID}_plugin.cpp)
  set_target_properties(busdecode_${D_ID} PROPERTIES AUTOMOC ON
    LIBRARY_OUTPUT_DIRECTORY ${BUSDECODE_PLUGIN_DIR} PREFIX "")
  target_link_libraries(busdecode_${D_ID} PRIVATE decoder_${D_ID} busdecode_plugin_api)
  install(TARGETS busdecode_${D_ID} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/busdecode/plugins)
  set_property(GLOBAL APPEND PROPERTY BUSDECODE_PLUGINS busdecode_${D_ID})
endfunction()

# busdecode_test(NAME <name> SOURCES <files...> [LIBS <targets...>] [LABELS <labels>])
#   A GoogleTest executable registered with CTest (one CTest entry per test case).
function(busdecode_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE busdecode_testsupport ${T_LIBS} GTest::gtest GTest::gtest_main)
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  set(_props TIMEOUT ${T_TIMEOUT})
  if(T_LABELS)
    list(APPEND _props LABELS "${T_LABELS}")
  endif()
  gtest_discover_tests(${T_NAME} WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    PROPERTIES ${_props} DISCOVERY_TIMEOUT 60)
endfunction()
