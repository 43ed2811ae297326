# bench_pd's --pairs selects haptic pairs too: one haptic pair alone runs the
# haptic scenario on that pair alone; a name of no pair is an error naming it.
include(${CMAKE_CURRENT_LIST_DIR}/require_meshes.cmake)
require_meshes("${MESH_DIR}" knot1.off camel.off)
include(${CMAKE_CURRENT_LIST_DIR}/bench_pd_script.cmake)
file(REMOVE_RECURSE "${OUT}")
run_bench_pd(${OUT} --quick --haptic-ref 0 --haptic-more-paths 0 --haptic-budget-us 0
             --pairs knot1_camel --mesh-dir ${MESH_DIR})
file(STRINGS "${OUT}/pd_haptic_paths.csv" lines)
list(LENGTH lines n)
if(NOT n EQUAL 2)
  message(FATAL_ERROR "expected the header and knot1_camel's one path, got: ${lines}")
endif()
list(GET lines 1 row)
if(NOT row MATCHES "^knot1_camel,")
  message(FATAL_ERROR "expected knot1_camel's path, got: ${row}")
endif()
if(EXISTS "${OUT}/pd_cases.csv")
  message(FATAL_ERROR "a haptic pair alone ran the other scenarios too (pd_cases.csv written)")
endif()
execute_process(COMMAND ${BENCH} --quick --pairs no_such_pair --mesh-dir ${MESH_DIR}
                        --out ${OUT}/unknown
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(rc EQUAL 0 OR NOT err MATCHES "no pair named no_such_pair")
  message(FATAL_ERROR "--pairs no_such_pair: expected an error naming it, got exit ${rc}: ${err}")
endif()
