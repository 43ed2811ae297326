# pd_build_info: the generated header that says what this build is
# (version, build type, CPU level; scripts/cmake/build_info.h.in).
# How a build names itself, up to the compiler (which only the preprocessor
# knows): build_info.h's Summary() and the tests of --version both use it.
set(PD_BUILD_SUMMARY_PREFIX "${PROJECT_VERSION} (${CMAKE_BUILD_TYPE}, ${PD_CPU_LEVEL_RESOLVED}, ")
configure_file(${CMAKE_CURRENT_LIST_DIR}/build_info.h.in
               ${CMAKE_BINARY_DIR}/generated/pd_build/build_info.h @ONLY)
add_library(pd_build_info INTERFACE)
target_include_directories(pd_build_info INTERFACE ${CMAKE_BINARY_DIR}/generated)
