# `cubtool join --all --routes-out` on the shipped assets reproduces the
# committed routes (assets/clips/bear.routes.txt) byte for byte. Run by
# ctest: -DCUBTOOL= -DSRC= -DOUT=
execute_process(COMMAND ${CUBTOOL} join --all --assets ${SRC}/assets --routes-out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE progress)
string(REGEX MATCHALL "join --all: routes:[^\n]*" lines "${summary}")
message("${lines}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cubtool join --all failed (${rc}):\n${progress}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}
                        ${SRC}/assets/clips/bear.routes.txt RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "${OUT} differs from assets/clips/bear.routes.txt: re-run "
                      "`cubtool join --all --routes-out assets/clips/bear.routes.txt` and look "
                      "at why (docs/join.md, \"Routes\")")
endif()
message("check_routes: cubtool join --all reproduces assets/clips/bear.routes.txt byte for byte")
