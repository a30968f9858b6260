# busdecode_direct_feed: a decoder fed edges directly, three ways (direct_feed.h), for the
# decoders' tests and the fuzz harness. Included by both; defines the target once.
if(NOT TARGET busdecode_direct_feed)
  add_library(busdecode_direct_feed STATIC ${CMAKE_CURRENT_LIST_DIR}/direct_feed.cpp)
  target_include_directories(busdecode_direct_feed PUBLIC ${CMAKE_CURRENT_LIST_DIR}/../..)
  target_link_libraries(busdecode_direct_feed PUBLIC busdecode_core)
endif()
