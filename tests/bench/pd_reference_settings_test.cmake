# bench_pd's --ref-directions sets the reference's directions in the random,
# path and shallow scenarios; the haptic scenario's reference keeps its own
# (the settings its warm-PD targets were measured at), and the reports say
# which each used.
cmake_policy(SET CMP0007 NEW)  # keep the CSV's empty fields as list elements
include(${CMAKE_CURRENT_LIST_DIR}/require_meshes.cmake)
require_meshes("${MESH_DIR}" knot1.off camel.off)
file(REMOVE_RECURSE "${OUT}")

include(${CMAKE_CURRENT_LIST_DIR}/bench_pd_script.cmake)
function(run_bench label)
  run_bench_pd(${OUT}/${label} ${ARGN} --mesh-dir ${MESH_DIR})
endfunction()

run_bench(random --quick --scenarios random --pairs torus_knot_3k --random-cases 2 --ref-random 1
          --no-sweep --ref-directions 300)
# One reference row, its 300 directions then at most 4 refinement starts x
# 32 evaluations (--quick).
rows_with("${OUT}/random/pd_cases.csv" ref_depth_m ref_directions 300 428 1 rows)
file(READ "${OUT}/random/pd_speed_error.md" md)
if(NOT md MATCHES "300 Fibonacci directions, 4 refinement starts x 32 evaluations")
  message(FATAL_ERROR "pd_speed_error.md does not state the reference's settings (300 x 32)")
endif()
# Times move with the CPU level the code was compiled for: the report says which.
if(NOT md MATCHES "\\| Build type, CPU level \\| [A-Za-z]+, ${CPU_LEVEL} \\(")
  message(FATAL_ERROR "pd_speed_error.md does not state the build's CPU level (${CPU_LEVEL})")
endif()

# The haptic reference: its own 96 directions (quick), whatever --ref-directions.
run_bench(haptic --quick --haptic-ref 1 --haptic-more-paths 0 --haptic-budget-us 0
          --pairs knot1_camel --ref-directions 300)
rows_with("${OUT}/haptic/pd_haptic.csv" ref_depth_m ref_directions 96 224 1 rows)
file(READ "${OUT}/haptic/pd_haptic.md" md)
if(NOT md MATCHES "no hint \\(96 directions, 4 refinement starts x 32 evaluations\\)")
  message(FATAL_ERROR "pd_haptic.md: the haptic reference did not state its own settings (96 x 32)")
endif()
