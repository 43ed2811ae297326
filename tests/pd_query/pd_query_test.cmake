# End-to-end checks of the pd_query tool, run with cmake -P.
#   -DPD_QUERY=<binary> -DCASE=<name> -DWORK_DIR=<scratch directory>
# Meshes are boxes written here, so every expected depth is an analytic
# overlap. Any failed check ends the script with FATAL_ERROR (test fails).
cmake_minimum_required(VERSION 3.20)

foreach(var PD_QUERY CASE WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "pass -D${var}=...")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# ------------------------------------------------------------------ helpers

# Axis-aligned box centred at the origin with half extents hx hy hz (positive
# decimal literals), outward quads. Vertex k has the sign of bit 0/1/2 on x/y/z.
function(write_box path hx hy hz)
  set(text "OFF\n8 6 0\n")
  foreach(k RANGE 7)
    set(line "")
    foreach(axis 0 1 2)
      math(EXPR positive "(${k} >> ${axis}) & 1")
      if(axis EQUAL 0)
        set(h ${hx})
      elseif(axis EQUAL 1)
        set(h ${hy})
      else()
        set(h ${hz})
      endif()
      if(positive)
        string(APPEND line "${h} ")
      else()
        string(APPEND line "-${h} ")
      endif()
    endforeach()
    string(APPEND text "${line}\n")
  endforeach()
  string(APPEND text "4 0 4 6 2\n4 1 3 7 5\n4 0 1 5 4\n4 2 6 7 3\n4 0 2 3 1\n4 4 5 7 6\n")
  file(WRITE "${path}" "${text}")
endfunction()

# Runs pd_query with stdin `input` and the remaining arguments; sets RC, OUT,
# ERR and the output lines LINE_1 .. LINE_<NUM_LINES> in the caller.
function(run_pd_query input)
  file(WRITE "${WORK_DIR}/stdin.txt" "${input}")
  execute_process(COMMAND "${PD_QUERY}" ${ARGN}
                  INPUT_FILE "${WORK_DIR}/stdin.txt"
                  OUTPUT_VARIABLE out
                  ERROR_VARIABLE err
                  RESULT_VARIABLE rc
                  TIMEOUT 300)
  set(RC "${rc}" PARENT_SCOPE)
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
  # Split by hand: CMake lists treat brackets specially, JSON is full of them.
  set(n 0)
  set(rest "${out}")
  while(NOT rest STREQUAL "")
    string(FIND "${rest}" "\n" nl)
    if(nl EQUAL -1)
      set(line "${rest}")
      set(rest "")
    else()
      string(SUBSTRING "${rest}" 0 ${nl} line)
      math(EXPR next "${nl} + 1")
      string(SUBSTRING "${rest}" ${next} -1 rest)
    endif()
    math(EXPR n "${n} + 1")
    set(LINE_${n} "${line}" PARENT_SCOPE)
  endwhile()
  set(NUM_LINES ${n} PARENT_SCOPE)
  message(STATUS "pd_query ${ARGN}: exit ${rc}, ${n} lines\n${out}${err}")
endfunction()

function(fail what)
  message(FATAL_ERROR "[${CASE}] ${what}")
endfunction()

function(expect_equal actual expected what)
  if(NOT "${actual}" STREQUAL "${expected}")
    fail("${what}: got '${actual}', expected '${expected}'")
  endif()
endfunction()

function(expect_contains text needle what)
  string(FIND "${text}" "${needle}" at)
  if(at EQUAL -1)
    fail("${what}: '${needle}' not found in:\n${text}")
  endif()
endfunction()

# JSON member at the path given by the remaining arguments of `json`.
function(json_get out json)
  string(JSON value ERROR_VARIABLE error GET "${json}" ${ARGN})
  if(error)
    fail("JSON '${json}' has no ${ARGN}: ${error}")
  endif()
  set(${out} "${value}" PARENT_SCOPE)
endfunction()

# The probe slides into the unit cube along -x, step_mm millimetres per line
# from x = 0.95 (7 lines, depth = 1 - x), answered cold or with --coherent. A
# macro, so the caller gets RC, NUM_LINES and LINE_1 .. LINE_7.
macro(run_slide step_mm mode)
  set(slide_input "")
  foreach(slide_step RANGE 0 6)
    math(EXPR slide_x_mm "950 - ${step_mm} * ${slide_step}")
    string(APPEND slide_input "0.${slide_x_mm} 0.01 0 1 0 0 0\n")
  endforeach()
  if("${mode}" STREQUAL "coherent")
    run_pd_query("${slide_input}" "${BOX}" "${BOX}" --coherent)
  else()
    run_pd_query("${slide_input}" "${BOX}" "${BOX}")
  endif()
  expect_equal("${RC}" 0 "${mode} exit code")
  expect_equal("${NUM_LINES}" 7 "${mode} answers")
endmacro()

# lo <= json[path] <= hi (CMake compares numbers as doubles).
function(expect_between json lo hi)
  json_get(value "${json}" ${ARGN})
  if(NOT (value GREATER_EQUAL lo AND value LESS_EQUAL hi))
    fail("${ARGN} = ${value}, expected within [${lo}, ${hi}] in ${json}")
  endif()
endfunction()

# A colliding answer whose PD is within [depth_lo, depth_hi] along the signed
# unit axis (+x, -y, ...), with well-formed contact regions.
function(expect_pd json depth_lo depth_hi signed_axis)
  json_get(collision "${json}" collision)
  expect_equal("${collision}" "ON" "collision")
  json_get(valid "${json}" valid)
  expect_equal("${valid}" "ON" "valid")
  expect_between("${json}" ${depth_lo} ${depth_hi} depth)
  string(SUBSTRING "${signed_axis}" 0 1 sign)
  string(SUBSTRING "${signed_axis}" 1 1 axis)
  set(index_x 0)
  set(index_y 1)
  set(index_z 2)
  foreach(a x y z)
    if(NOT a STREQUAL axis)
      expect_between("${json}" -1e-5 1e-5 normal ${index_${a}})
    elseif(sign STREQUAL "+")
      expect_between("${json}" 0.99999 1.00001 normal ${index_${a}})
      expect_between("${json}" ${depth_lo} ${depth_hi} translation ${index_${a}})
    else()
      expect_between("${json}" -1.00001 -0.99999 normal ${index_${a}})
      expect_between("${json}" -${depth_hi} -${depth_lo} translation ${index_${a}})
    endif()
  endforeach()
  json_get(initializer "${json}" initializer)
  if(initializer STREQUAL "" OR initializer STREQUAL "none")
    fail("initializer '${initializer}' for a colliding pose")
  endif()
  expect_between("${json}" 0 1e9 iterations)
  expect_between("${json}" 1 1e9 contacts)
  expect_between("${json}" 1e-9 1e9 time_us)
  string(JSON num_regions LENGTH "${json}" regions)
  if(num_regions LESS 1)
    fail("no contact regions in ${json}")
  endif()
  math(EXPR last "${num_regions} - 1")
  foreach(i RANGE ${last})
    string(JSON n LENGTH "${json}" regions ${i} point)
    expect_equal("${n}" 3 "region ${i} point size")
    string(JSON n LENGTH "${json}" regions ${i} normal)
    expect_equal("${n}" 3 "region ${i} normal size")
    expect_between("${json}" 0 ${depth_hi} regions ${i} local_depth)
  endforeach()
endfunction()

# "0.ddddd" for an integer count of 1e-5 below 1e5.
function(decimal_from_1e5 out count)
  string(LENGTH "${count}" digits)
  math(EXPR pad "5 - ${digits}")
  string(REPEAT "0" ${pad} zeros)
  set(${out} "0.${zeros}${count}" PARENT_SCOPE)
endfunction()

function(expect_free json)
  json_get(collision "${json}" collision)
  expect_equal("${collision}" "OFF" "collision")
  expect_between("${json}" 0 0 depth)
endfunction()

set(BOX "${WORK_DIR}/box.off")  # unit cube, half extents 0.5 m
write_box("${BOX}" 0.5 0.5 0.5)
# 45 degrees about z, w first: (cos 22.5, 0, 0, sin 22.5).
set(QZ45 "0.9238795325112867 0 0 0.3826834323650898")  # in stdin text
separate_arguments(QZ45_ARGS UNIX_COMMAND "${QZ45}")     # as arguments

# -------------------------------------------------------------------- cases

if(CASE STREQUAL "command_line")
  run_pd_query("" --help)
  expect_equal("${RC}" 0 "--help exit code")
  foreach(needle "x y z qw qx qy qz" "metres" "w first" "Exit codes" "--coherent" "--scene-pose")
    expect_contains("${OUT}" "${needle}" "--help text")
  endforeach()
  run_pd_query("")
  expect_equal("${RC}" 3 "no arguments")
  run_pd_query("" "${BOX}" "${BOX}" --scene-pose 0 0 0 2 0 0 0)
  expect_equal("${RC}" 3 "non-unit --scene-pose")
  expect_contains("${ERR}" "--scene-pose" "scene pose error")
  run_pd_query("" "${BOX}" "${BOX}" --scene-pose 0 0 0)
  expect_equal("${RC}" 3 "short --scene-pose")

elseif(CASE STREQUAL "missing_mesh")
  set(missing "${WORK_DIR}/no_such_probe.off")
  run_pd_query("0 0 0 1 0 0 0\n" "${missing}" "${BOX}")
  expect_equal("${RC}" 1 "missing probe")
  expect_contains("${ERR}" "${missing}" "missing probe message")
  expect_equal("${OUT}" "" "stdout with a missing probe")
  run_pd_query("0 0 0 1 0 0 0\n" "${BOX}" "${WORK_DIR}/no_such_scene.stl")
  expect_equal("${RC}" 1 "missing scene")
  expect_contains("${ERR}" "no_such_scene.stl: file not found" "missing scene message")
  set(broken "${WORK_DIR}/nan.off")
  file(WRITE "${broken}" "OFF\n4 4 0\n0 0 0\n1 0 0\n0 nan 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
  run_pd_query("0 0 0 1 0 0 0\n" "${BOX}" "${broken}")
  expect_equal("${RC}" 1 "NaN scene")
  expect_contains("${ERR}" "${broken}: non-finite" "NaN scene message")
  run_pd_query("" "${BOX}" "${BOX}" --probe-scale -1)
  expect_equal("${RC}" 1 "negative scale")
  expect_contains("${ERR}" "scale" "negative scale message")
  # An open mesh loads with a warning naming it.
  set(open "${WORK_DIR}/open_box.off")
  file(READ "${BOX}" text)
  string(REPLACE "8 6 0" "8 5 0" text "${text}")
  string(REPLACE "4 4 5 7 6\n" "" text "${text}")
  file(WRITE "${open}" "${text}")
  run_pd_query("5 0 0 1 0 0 0\n" "${BOX}" "${open}")
  expect_equal("${RC}" 0 "open scene")
  expect_contains("${ERR}" "warning: ${open} is open" "open scene warning")
  expect_free("${LINE_1}")

elseif(CASE STREQUAL "overlapping_boxes")
  run_pd_query("# x y z qw qx qy qz\n0.8 0 0 1 0 0 0\n\n0 0 0.7 1 0 0 0\n2 0 0 1 0 0 0\n1.1 0 0 ${QZ45}\n0 -0.95 0.1 1 0 0 0\n"
               "${BOX}" "${BOX}")
  expect_equal("${RC}" 0 "exit code")
  expect_equal("${NUM_LINES}" 5 "answers (comment and blank skipped)")
  expect_pd("${LINE_1}" 0.19999 0.20001 +x)   # overlap 1 - 0.8 along x
  expect_pd("${LINE_2}" 0.29999 0.30001 +z)
  expect_free("${LINE_3}")
  # Rotated 45 degrees: its edge reaches 1.1 - sqrt(1/2) into the face x = 0.5.
  expect_pd("${LINE_4}" 0.10710 0.10712 +x)
  expect_pd("${LINE_5}" 0.04999 0.05001 -y)  # pushed out towards -y

elseif(CASE STREQUAL "malformed_lines")
  # Line 8 holds a byte that is not UTF-8, echoed back in the error.
  string(ASCII 255 not_utf8)
  run_pd_query("0.8 0 0 1 0 0 0\n1 2 3\n\n0 0 0 nan 0 0 0\n0 0 0 0 0 0 0\na b c d e f g\n0.8 0 0 1 0 0 0\n${not_utf8} 0 0 1 0 0 0\n"
               "${BOX}" "${BOX}")
  expect_equal("${RC}" 2 "exit code with malformed lines")
  expect_equal("${NUM_LINES}" 7 "one answer per non-blank line")
  json_get(error "${LINE_7}" error)
  expect_contains("${error}" "line 8: field x" "error of a non-UTF-8 line")
  expect_pd("${LINE_1}" 0.19999 0.20001 +x)
  foreach(i_n "2;2" "3;4" "4;5" "5;6")
    list(GET i_n 0 i)
    list(GET i_n 1 n)
    json_get(error "${LINE_${i}}" error)
    expect_contains("${error}" "line ${n}: " "error of input line ${n}")
  endforeach()
  json_get(error "${LINE_2}" error)
  expect_contains("${error}" "got 3 fields" "field count error")
  json_get(error "${LINE_3}" error)
  expect_contains("${error}" "not finite" "NaN error")
  json_get(error "${LINE_4}" error)
  expect_contains("${error}" "norm 0" "zero quaternion error")
  expect_pd("${LINE_6}" 0.19999 0.20001 +x)

elseif(CASE STREQUAL "scene_pose_and_scale")
  set(big "${WORK_DIR}/big_box.off")     # half 1, scaled by 0.5 -> unit cube
  set(small "${WORK_DIR}/small_box.off") # half 0.25, scaled by 2 -> unit cube
  write_box("${big}" 1 1 1)
  write_box("${small}" 0.25 0.25 0.25)
  # Scene cube centred at z = 1: the probe at z = 1.9 overlaps it by 0.1.
  run_pd_query("0 0 1.9 1 0 0 0\n0 0 3 1 0 0 0\n" "${big}" "${small}" --probe-scale 0.5
               --scene-scale 2 --scene-pose 0 0 1 1 0 0 0)
  expect_equal("${RC}" 0 "exit code")
  expect_pd("${LINE_1}" 0.09999 0.10001 +z)
  expect_free("${LINE_2}")
  # Scene turned 45 degrees about z: its edge reaches x = sqrt(1/2).
  run_pd_query("1.1 0 1 1 0 0 0\n" "${big}" "${small}" --probe-scale 0.5 --scene-scale 2
               --scene-pose 0 0 1 ${QZ45_ARGS})
  expect_equal("${RC}" 0 "exit code")
  expect_pd("${LINE_1}" 0.10710 0.10712 +x)

elseif(CASE STREQUAL "budget")
  # Bounded time: a spent budget stops the search after its first verified
  # answer (converged false, still valid and an upper bound); no budget
  # converges; a negative budget is a usage error.
  set(input "0.8 0.05 0.02 ${QZ45}\n")
  run_pd_query("${input}" "${BOX}" "${BOX}")
  expect_equal("${RC}" 0 "unbounded exit code")
  json_get(converged "${LINE_1}" converged)
  expect_equal("${converged}" ON "unbounded converged")
  json_get(exact "${LINE_1}" depth)
  run_pd_query("${input}" "${BOX}" "${BOX}" --max-time-us 0.001)
  expect_equal("${RC}" 0 "bounded exit code")
  json_get(converged "${LINE_1}" converged)
  expect_equal("${converged}" OFF "bounded converged")
  json_get(valid "${LINE_1}" valid)
  expect_equal("${valid}" ON "bounded valid")
  json_get(bounded "${LINE_1}" depth)
  if(bounded LESS exact)
    fail("bounded depth ${bounded} below the converged ${exact}")
  endif()
  run_pd_query("${input}" "${BOX}" "${BOX}" --max-work -1)
  expect_equal("${RC}" 3 "negative budget exit code")

elseif(CASE STREQUAL "coherent")
  # Depth = 1 - x on every line, answered cold by default and warm-started
  # with --coherent.
  foreach(mode cold coherent)
    run_slide(30 ${mode})
    set(warm 0)
    foreach(step RANGE 0 6)
      math(EXPR line "${step} + 1")
      math(EXPR depth_mm "50 + 30 * ${step}")
      math(EXPR lo "${depth_mm} * 100 - 1")  # in 1e-5 m
      math(EXPR hi "${depth_mm} * 100 + 1")
      decimal_from_1e5(lo ${lo})
      decimal_from_1e5(hi ${hi})
      expect_pd("${LINE_${line}}" ${lo} ${hi} +x)
      json_get(initializer "${LINE_${line}}" initializer)
      if(initializer STREQUAL "motion_coherence")
        math(EXPR warm "${warm} + 1")
      endif()
    endforeach()
    if(mode STREQUAL "cold" AND warm GREATER 0)
      fail("cold lines used the previous answer")
    endif()
    if(mode STREQUAL "coherent" AND warm EQUAL 0)
      fail("--coherent never started from the previous answer")
    endif()
  endforeach()

elseif(CASE STREQUAL "coherent_list_reuse")
  # The probe slides 3 mm per line: a warm query keeps a list of the leaf
  # pairs near the contact and reuses it while the probe stays within its
  # reach. Cold lines never build one; warm lines build one and then reuse
  # it; a line that builds reports the time spent, within its own time.
  foreach(mode cold coherent)
    run_slide(3 ${mode})
    set(builds 0)
    set(reused 0)
    foreach(line RANGE 1 7)
      json_get(n "${LINE_${line}}" list_builds)
      json_get(total "${LINE_${line}}" time_us)
      if(n GREATER 0)
        math(EXPR builds "${builds} + ${n}")
        expect_between("${LINE_${line}}" 1e-9 ${total} list_build_us)
      else()
        expect_between("${LINE_${line}}" 0 0 list_build_us)  # no build, no build time
        if(line GREATER 1)
          math(EXPR reused "${reused} + 1")
        endif()
      endif()
    endforeach()
    if(mode STREQUAL "cold")
      expect_equal("${builds}" 0 "cold lines: list builds")
    elseif(builds EQUAL 0 OR reused EQUAL 0)
      fail("--coherent: ${builds} list builds, ${reused} warm lines reusing a list (expected both > 0)")
    endif()
  endforeach()

elseif(CASE STREQUAL "multi_part_containment")
  # Issue 12: two cubes of half-size 0.01 in one file, the far one (x = 0.1)
  # listed first, against a cube of half-size 0.025 at the origin that
  # wholly contains the other part (no surface crossing). Either mesh as
  # the probe: colliding, PD 0.025 + 0.01 = 0.035 along any axis (a tie).
  set(parts "${WORK_DIR}/two_cubes.off")  # far cube (x = 0.1) first, then the one at 0
  set(text "OFF\n16 12 0\n0.09 -0.01 -0.01\n0.11 -0.01 -0.01\n0.09 0.01 -0.01\n0.11 0.01 -0.01\n0.09 -0.01 0.01\n0.11 -0.01 0.01\n0.09 0.01 0.01\n0.11 0.01 0.01\n-0.01 -0.01 -0.01\n0.01 -0.01 -0.01\n-0.01 0.01 -0.01\n0.01 0.01 -0.01\n-0.01 -0.01 0.01\n0.01 -0.01 0.01\n-0.01 0.01 0.01\n0.01 0.01 0.01\n4 0 4 6 2\n4 1 3 7 5\n4 0 1 5 4\n4 2 6 7 3\n4 0 2 3 1\n4 4 5 7 6\n4 8 12 14 10\n4 9 11 15 13\n4 8 9 13 12\n4 10 14 15 11\n4 8 10 11 9\n4 12 13 15 14\n")
  file(WRITE "${parts}" "${text}")
  set(cube "${WORK_DIR}/cube_0025.off")
  write_box("${cube}" 0.025 0.025 0.025)
  foreach(order "parts;cube" "cube;parts")
    list(GET order 0 probe)
    list(GET order 1 scene)
    run_pd_query("0 0 0 1 0 0 0\n" "${${probe}}" "${${scene}}")
    expect_equal("${RC}" 0 "${probe} as probe: exit code")
    json_get(collision "${LINE_1}" collision)
    expect_equal("${collision}" "ON" "${probe} as probe: collision")
    json_get(valid "${LINE_1}" valid)
    expect_equal("${valid}" "ON" "${probe} as probe: valid")
    expect_between("${LINE_1}" 0.034999 0.035001 depth)
    set(axis_aligned 0)
    foreach(i 0 1 2)
      json_get(n "${LINE_1}" normal ${i})
      if(n GREATER_EQUAL 0.99999 OR n LESS_EQUAL -0.99999)
        math(EXPR axis_aligned "${axis_aligned} + 1")
      endif()
    endforeach()
    expect_equal("${axis_aligned}" 1 "${probe} as probe: normal along one axis")
  endforeach()

else()
  fail("unknown CASE")
endif()
