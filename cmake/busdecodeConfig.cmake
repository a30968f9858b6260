# Lets out-of-tree decoder plugins find the installed core: find_package(busdecode).
include(CMakeFindDependencyMacro)
find_dependency(Qt6 COMPONENTS Core)
find_dependency(fmt)
include(${CMAKE_CURRENT_LIST_DIR}/busdecodeTargets.cmake)
