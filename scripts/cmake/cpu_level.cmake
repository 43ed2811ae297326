# PD_CPU_LEVEL: the x86-64 level the project is compiled for.
#   auto       x86-64-v3 if the machine configuring the build can run it (AVX2,
#              FMA, BMI2: Intel Haswell / AMD Excavator and later), else the
#              compiler's default
#   x86-64     baseline: runs on every x86-64 (a package for other machines)
#   x86-64-v3  AVX2 and the rest of level 3
# The answers are the same at every level, bit for bit: pd_core turns off
# Eigen's own SIMD code and floating-point contraction (pd_core/CMakeLists.txt),
# the two things that make them depend on the instruction set. What a higher
# level buys is the compiler's use of the wider registers and three-operand
# instructions in the box and triangle tests.
set(PD_CPU_LEVEL auto CACHE STRING "x86-64 level to compile for: auto, x86-64 or x86-64-v3")
set_property(CACHE PD_CPU_LEVEL PROPERTY STRINGS auto x86-64 x86-64-v3)
if(NOT PD_CPU_LEVEL MATCHES "^(auto|x86-64|x86-64-v3)$")
  message(FATAL_ERROR "PD_CPU_LEVEL: '${PD_CPU_LEVEL}' is not one of auto, x86-64, x86-64-v3")
endif()
set(pd_x86 OFF)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  set(pd_x86 ON)
endif()
if(NOT pd_x86 AND NOT PD_CPU_LEVEL STREQUAL "auto")
  message(FATAL_ERROR "PD_CPU_LEVEL: '${PD_CPU_LEVEL}' is an x86-64 level; this build targets "
                      "${CMAKE_SYSTEM_PROCESSOR} (use auto)")
endif()
set(PD_CPU_LEVEL_RESOLVED default)  # not x86-64, or cross-compiling: the compiler's default
if(PD_CPU_LEVEL STREQUAL "auto" AND pd_x86 AND NOT CMAKE_CROSSCOMPILING)
  include(CheckCXXSourceRuns)
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag(-march=x86-64-v3 PD_COMPILER_HAS_X86_64_V3)
  check_cxx_source_runs([=[
    int main() {
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
                     __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                     __builtin_cpu_supports("bmi2") ? 0 : 1;
    }]=] PD_HOST_RUNS_X86_64_V3)
  if(PD_COMPILER_HAS_X86_64_V3 AND PD_HOST_RUNS_X86_64_V3)
    set(PD_CPU_LEVEL_RESOLVED x86-64-v3)
  else()
    set(PD_CPU_LEVEL_RESOLVED x86-64)
  endif()
elseif(NOT PD_CPU_LEVEL STREQUAL "auto")
  set(PD_CPU_LEVEL_RESOLVED ${PD_CPU_LEVEL})
endif()
if(PD_CPU_LEVEL_RESOLVED MATCHES "^x86-64")
  add_compile_options(-march=${PD_CPU_LEVEL_RESOLVED})
  # Eigen aligns its fixed-size objects to the instruction set's register
  # width (32 bytes with AVX): kept at 16 in every target, the layout that
  # FCL, assimp's users and any other Debian-built Eigen code expect.
  add_compile_definitions(EIGEN_MAX_ALIGN_BYTES=16 EIGEN_MAX_STATIC_ALIGN_BYTES=16)
endif()
message(STATUS "PD_CPU_LEVEL: ${PD_CPU_LEVEL} -> ${PD_CPU_LEVEL_RESOLVED}")
