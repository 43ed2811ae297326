# bench_pd reports the starts a cold query landed and iterated (issue 13:
# "report the iterations and starts actually used"): pd_cases.csv's
# pd_starts and pd_iterated_starts on every colliding random case, and the
# results table's "Starts landed / iterated" column. With the default options
# a cold query lands the 96 support-plane starts and the centroid start (more
# when the shell and inner probes out-project theirs) and iterates at least
# one, at most its 3 starts, 4 shell probes and 2 inner probes; each iterated
# start takes at least one iteration.
cmake_policy(SET CMP0007 NEW)  # keep the CSV's empty fields as list elements
include(${CMAKE_CURRENT_LIST_DIR}/bench_pd_script.cmake)
file(REMOVE_RECURSE "${OUT}")
run_bench_pd(${OUT} --quick --scenarios random --pairs torus_knot_3k --random-cases 6
             --ref-random 1 --no-sweep)
read_csv("${OUT}/pd_cases.csv" c scenario colliding pd_iterations pd_starts pd_iterated_starts)
set(checked 0)
foreach(line IN LISTS c_rows)
  string(REPLACE "," ";" f "${line}")
  list(GET f ${c_scenario} scenario)
  list(GET f ${c_colliding} colliding)
  if(NOT scenario STREQUAL "random" OR NOT colliding EQUAL 1)
    continue()
  endif()
  list(GET f ${c_pd_starts} starts)
  list(GET f ${c_pd_iterated_starts} iterated)
  list(GET f ${c_pd_iterations} iterations)
  if(starts LESS 97)
    message(FATAL_ERROR "a cold query landed ${starts} starts, fewer than 96 + 1: ${line}")
  endif()
  if(iterated LESS 1 OR iterated GREATER 9)
    message(FATAL_ERROR "a cold query iterated ${iterated} starts, not 1-9: ${line}")
  endif()
  if(iterations LESS iterated)
    message(FATAL_ERROR "${iterations} iterations over ${iterated} iterated starts: ${line}")
  endif()
  math(EXPR checked "${checked} + 1")
endforeach()
if(checked LESS 6)
  message(FATAL_ERROR "expected 6 colliding random cases, checked ${checked}")
endif()

file(READ "${OUT}/pd_speed_error.md" md)
if(NOT md MATCHES "\\| Starts landed / iterated mean \\|")
  message(FATAL_ERROR "pd_speed_error.md's results table lacks the starts column")
endif()
if(NOT md MATCHES "\\| torus_knot_3k \\([0-9]+ vs [0-9]+\\) \\| random \\| 6 \\|[^\n]*\\| 9[7-9]\\.[0-9] / [1-9]\\.[0-9][0-9] \\|")
  message(FATAL_ERROR "pd_speed_error.md: no torus_knot_3k random row with starts landed / iterated")
endif()
