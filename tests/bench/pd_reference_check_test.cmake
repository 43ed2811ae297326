# bench_pd checks its own reference: --ref-check N of each small pair's
# random reference cases are solved again by a reference at 4x the
# directions, 4x the evaluations per refinement start and 2x the starts
# (pd_cases.csv's ref_check_depth_m and ref_check_directions), and the
# report's "checked by a heavier one" table gives how far the reference was
# above the check and PolyDepth's error against each. --ref-check 0: none.
cmake_policy(SET CMP0007 NEW)  # keep the CSV's empty fields as list elements
include(${CMAKE_CURRENT_LIST_DIR}/bench_pd_script.cmake)
file(REMOVE_RECURSE "${OUT}")

# Rows of the CSV with a check: `expected` of them, each having evaluated
# its 384 sphere directions plus at most 8 x 128 refinement evaluations,
# each a random reference case with a real depth.
function(check_rows csv expected)
  rows_with("${csv}" ref_check_depth_m ref_check_directions 384 1408 ${expected} rows)
  read_csv("${csv}" c scenario ref_depth_m ref_check_depth_m)
  foreach(line IN LISTS rows)
    string(REPLACE "," ";" f "${line}")
    list(GET f ${c_scenario} scenario)
    list(GET f ${c_ref_depth_m} ref)
    list(GET f ${c_ref_check_depth_m} check)
    if(NOT scenario STREQUAL "random" OR ref STREQUAL "")
      message(FATAL_ERROR "${csv}: a check on a case that is not a random reference case: ${line}")
    endif()
    # Two upper bounds on the same case's PD, both a real depth (the models'
    # bounding spheres have radius 0.1 m).
    if(NOT check GREATER 0 OR NOT check LESS 0.2)
      message(FATAL_ERROR "${csv}: check ${check} m (reference ${ref} m): ${line}")
    endif()
  endforeach()
endfunction()

run_bench_pd(${OUT}/check --quick --scenarios random --pairs torus_knot_3k --random-cases 6
             --ref-random 3 --ref-check 2 --no-sweep)
check_rows("${OUT}/check/pd_cases.csv" 2)
set(md "${OUT}/check/pd_speed_error.md")
expect_report("${md}" "## The reference checked by a heavier one" "lacks the reference check section")
expect_report("${md}" "384 directions, 8 refinement starts x 128 evaluations \\(the run's reference: 96, 4 x 32\\)"
              "does not state the check's settings (384, 8 x 128)")
expect_report("${md}" "\\| torus_knot_3k \\| 2 \\| [0-9.-]+% / [0-9.-]+% \\| [0-2] \\| [0-9.]+% / [0-9.]+% \\| [0-9.]+% / [0-9.]+% \\| [0-9.]+ s \\|"
              "no check row with 2 cases for torus_knot_3k")

run_bench_pd(${OUT}/none --quick --scenarios random --pairs torus_knot_3k --random-cases 6
             --ref-random 1 --ref-check 0 --no-sweep)
check_rows("${OUT}/none/pd_cases.csv" 0)
expect_report(NOT "${OUT}/none/pd_speed_error.md" "checked by a heavier one"
              "has a reference check section with --ref-check 0")
