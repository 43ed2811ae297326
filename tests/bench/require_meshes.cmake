# require_meshes(DIR FILE...): in a CTest script (cmake -P), a missing mesh
# is a skip ("SKIPPED:", matched by the test's SKIP_REGULAR_EXPRESSION), and
# under CI (CI=true) a failure: a missing prerequisite never passes quietly.
# A macro, so that its return() ends the calling script.
macro(require_meshes dir)
  foreach(mesh ${ARGN})
    if(NOT EXISTS "${dir}/${mesh}")
      if("$ENV{CI}" STREQUAL "true")
        message(FATAL_ERROR "meshes missing under ${dir} (run scripts/fetch_meshes.sh): a missing prerequisite fails in CI")
      endif()
      message("SKIPPED: meshes missing under ${dir} (run scripts/fetch_meshes.sh)")
      return()
    endif()
  endforeach()
endmacro()
