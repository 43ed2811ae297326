# Helpers of the bench_pd script tests (tests/bench/*_test.cmake).

# run_bench_pd(OUT_DIR ARG...): runs ${BENCH} ARG... --out OUT_DIR and fails,
# naming the arguments and bench_pd's stderr, unless it exits 0.
function(run_bench_pd out_dir)
  execute_process(COMMAND ${BENCH} ${ARGN} --out ${out_dir}
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "bench_pd ${ARGN} exited ${rc}: ${err}")
  endif()
endfunction()

# read_csv(CSV PREFIX COLUMN...): sets PREFIX_rows to the CSV's data lines
# and PREFIX_<COLUMN> to each named column's index; fails naming a column the
# header lacks. (Split a row into fields with string(REPLACE "," ";" ...)
# under CMP0007 NEW, which keeps empty fields.)
function(read_csv csv prefix)
  file(STRINGS "${csv}" lines)
  list(GET lines 0 header)
  string(REPLACE "," ";" columns "${header}")
  foreach(name ${ARGN})
    list(FIND columns "${name}" i)
    if(i LESS 0)
      message(FATAL_ERROR "${csv} lacks ${name}: ${header}")
    endif()
    set(${prefix}_${name} ${i} PARENT_SCOPE)
  endforeach()
  list(REMOVE_AT lines 0)
  set(${prefix}_rows "${lines}" PARENT_SCOPE)
endfunction()

# expect_report(FILE REGEX WHAT...): fails naming FILE's basename and WHAT
# unless FILE's text matches REGEX; with NOT first, unless it does not.
function(expect_report)
  set(negate FALSE)
  if(ARGV0 STREQUAL "NOT")
    set(negate TRUE)
    list(REMOVE_AT ARGV 0)
  endif()
  list(GET ARGV 0 file)
  list(GET ARGV 1 regex)
  list(SUBLIST ARGV 2 -1 what)
  string(JOIN " " what ${what})
  file(READ "${file}" text)
  get_filename_component(name "${file}" NAME)
  if(text MATCHES "${regex}")
    if(negate)
      message(FATAL_ERROR "${name}: ${what}")
    endif()
  elseif(NOT negate)
    message(FATAL_ERROR "${name}: ${what}")
  endif()
endfunction()

# rows_with(CSV COLUMN DIRS_COLUMN LO HI EXPECTED OUT): the CSV's data rows
# whose COLUMN is set (a reference's, or its check's, depth) go to OUT; fails
# unless there are EXPECTED of them and each evaluated between LO and HI
# directions (DIRS_COLUMN: its sphere, then its refinement evaluations).
function(rows_with csv column dirs_column lo hi expected out)
  read_csv("${csv}" c ${column} ${dirs_column})
  set(rows "")
  foreach(line IN LISTS c_rows)
    string(REPLACE "," ";" f "${line}")
    list(GET f ${c_${column}} value)
    if(value STREQUAL "")
      continue()
    endif()
    list(GET f ${c_${dirs_column}} dirs)
    if(dirs LESS ${lo} OR dirs GREATER ${hi})
      message(FATAL_ERROR "${csv}: ${dirs_column} ${dirs}, expected ${lo}-${hi}: ${line}")
    endif()
    list(APPEND rows "${line}")
  endforeach()
  list(LENGTH rows n)
  if(NOT n EQUAL ${expected})
    message(FATAL_ERROR "${csv}: expected ${expected} rows with ${column}, got ${n}")
  endif()
  set(${out} "${rows}" PARENT_SCOPE)
endfunction()
