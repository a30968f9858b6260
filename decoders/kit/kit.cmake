# The decoder kit (not shipped): the one Example shape every decoder's example captures
# take (example.h) and make_examples, which writes them all:
#   make_examples <repo>/captures [ID...]
# A decoder lists its examples in <id>_examples.cpp (busdecode_decoder(... EXAMPLES ...)),
# an OBJECT library linked whole, so that its listExamples() line runs.
include_guard(GLOBAL)
add_library(busdecode_examples STATIC ${CMAKE_CURRENT_LIST_DIR}/example.cpp)
target_include_directories(busdecode_examples PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(busdecode_examples PUBLIC busdecode_core busdecode_writers)

add_executable(make_examples ${CMAKE_CURRENT_LIST_DIR}/make_examples.cpp)
file(GLOB _example_lists ${CMAKE_SOURCE_DIR}/decoders/*/*_examples.h)
foreach(_list ${_example_lists})
  get_filename_component(_id ${_list} NAME_WE)
  string(REGEX REPLACE "_examples$" "" _id ${_id})
  # Only the decoders configured (BUSDECODE_DECODERS), known once all folders are read.
  target_link_libraries(make_examples PRIVATE $<TARGET_NAME_IF_EXISTS:examples_${_id}>)
endforeach()
target_link_libraries(make_examples PRIVATE busdecode_examples)
