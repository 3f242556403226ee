# `cubtool coach seal` on the shipped assets reproduces the committed
# second coach (assets/clips/seal.cubclips and seal.tags.xml) byte for byte.
# Run by ctest: -DCUBTOOL= -DSRC= -DOUT= (a folder)
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${CUBTOOL} coach seal --assets ${SRC}/assets --out-dir ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE progress)
string(REGEX MATCHALL "coach seal:[^\n]*" lines "${summary}")
message("${lines}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cubtool coach seal failed (${rc}):\n${progress}")
endif()
foreach(f seal.cubclips seal.tags.xml)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/${f}
                          ${SRC}/assets/clips/${f} RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "${OUT}/${f} differs from assets/clips/${f}: re-run "
                        "`cubtool coach seal` and look at why (docs/evolve.md, "
                        "\"The second coach\"; a changed bear library changes the seal's)")
  endif()
endforeach()
message("check_coach: cubtool coach seal reproduces assets/clips/seal.* byte for byte")
