# The slow reference PD is test and benchmark support (target pd_reference):
# the product library pd_core must not carry it, and must carry PolyDepth.
#   cmake -DNM=<nm> -DLIB=<libpd_core> -P pd_core_symbols_test.cmake
execute_process(COMMAND "${NM}" -C --defined-only "${LIB}" OUTPUT_VARIABLE symbols
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} ${LIB} failed (${rc}): ${err}")
endif()
string(FIND "${symbols}" "pd::PolyDepthSolver::Solve" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${LIB} defines no pd::PolyDepthSolver::Solve: wrong library?")
endif()
foreach(name ReferencePenetrationDepth ReferenceInCollision DirectionalPenetration)
  string(FIND "${symbols}" "pd::${name}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "${LIB} defines pd::${name}: the reference PD belongs in pd_reference")
  endif()
endforeach()
message(STATUS "${LIB}: PolyDepth present, no reference PD")
