# Checks the haptic paths themselves (bench/cases/haptic_paths.h): on every
# path bench_pd reports (seeds 20240611 to 20240616, all pairs), at every
# 20th colliding pose some translation no longer than twice the path's depth
# plus 2 mm frees the tool. Collision tests only, independent of PolyDepth.
include(${CMAKE_CURRENT_LIST_DIR}/require_meshes.cmake)
require_meshes("${MESH_DIR}" knot1.off bunny00.off)
foreach(seed RANGE 20240611 20240616)
  execute_process(COMMAND ${HAPTIC_WORK} --mesh-dir ${MESH_DIR} --seed ${seed}
                          --check-path-depth 20
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "seed ${seed}: haptic_work exited ${rc}:\n${out}\n${err}")
  endif()
  string(REGEX MATCHALL "path depth checked at [0-9]+ colliding poses" checked "${out}")
  list(LENGTH checked n)
  if(NOT n EQUAL 5)
    message(FATAL_ERROR "seed ${seed}: expected 5 pairs' path checks, got ${n}:\n${out}")
  endif()
  foreach(line ${checked})
    string(REGEX REPLACE ".* at ([0-9]+) colliding.*" "\\1" k "${line}")
    if(k LESS 50)
      message(FATAL_ERROR "seed ${seed}: too few colliding poses checked (${k}):\n${out}")
    endif()
  endforeach()
  message("seed ${seed}:\n${out}")
endforeach()
