# Runs bench_pd's quick haptic scenario (one more path per pair, one
# reference pose) and checks the CPU-time columns and row it reports.
include(${CMAKE_CURRENT_LIST_DIR}/require_meshes.cmake)
require_meshes("${MESH_DIR}" knot1.off camel.off)
include(${CMAKE_CURRENT_LIST_DIR}/bench_pd_script.cmake)
file(REMOVE_RECURSE "${OUT}")
run_bench_pd(${OUT} --quick --haptic-only --haptic-ref 1 --haptic-more-paths 1
             --mesh-dir ${MESH_DIR})
read_csv("${OUT}/pd_haptic_paths.csv" c max_us max_cpu_us budget_max_us budget_max_cpu_us)
list(LENGTH c_rows n)
if(n LESS 2)
  message(FATAL_ERROR "expected a row per path of each quick pair, got: ${c_rows}")
endif()
foreach(line IN LISTS c_rows)
  string(REPLACE "," ";" f "${line}")
  foreach(pair_of_columns "${c_max_us};${c_max_cpu_us}" "${c_budget_max_us};${c_budget_max_cpu_us}")
    list(GET pair_of_columns 0 iw)
    list(GET pair_of_columns 1 ic)
    list(GET f ${iw} wall)
    list(GET f ${ic} cpu)
    # CPU time is part of the wall time (its read, a system call, adds ~1 us),
    # up to the disagreement of the two clocks: on this KVM guest (kvm-clock,
    # TSC marked unstable) the thread CPU clock ran ahead of CLOCK_MONOTONIC by
    # up to 106 us over single 0.1-1 ms intervals (150k intervals with two
    # busy loops beside; up to 74 us with no context switch), and this check
    # failed at 50 us under ctest -j2. 250 us still catches a wrong unit or
    # interval (the deferred rebuild after Solve runs to the 1 ms pose period).
    if(NOT cpu MATCHES "^[0-9]" OR cpu LESS_EQUAL 0)
      message(FATAL_ERROR "no CPU time in: ${line}")
    endif()
    string(REGEX REPLACE "\\..*" "" wall_int "${wall}")
    math(EXPR limit "${wall_int} + 250")
    if(cpu GREATER ${limit})
      message(FATAL_ERROR "CPU time ${cpu} us above the wall time ${wall} us it is part of: ${line}")
    endif()
  endforeach()
endforeach()
file(READ "${OUT}/pd_haptic.md" md)
if(NOT md MATCHES "us of CPU time, bounded at 900 us, every path")
  message(FATAL_ERROR "pd_haptic.md lacks the CPU-time target row")
endif()
