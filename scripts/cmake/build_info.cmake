# pd_build_info: the generated header that says what this build is
# (version, build type, CPU level; scripts/cmake/build_info.h.in).
configure_file(${CMAKE_CURRENT_LIST_DIR}/build_info.h.in
               ${CMAKE_BINARY_DIR}/generated/pd_build/build_info.h @ONLY)
add_library(pd_build_info INTERFACE)
target_include_directories(pd_build_info INTERFACE ${CMAKE_BINARY_DIR}/generated)
