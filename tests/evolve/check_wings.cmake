# `cubtool wings` on the shipped assets reproduces the committed winged bear
# (assets/bear/bear_winged.xml, assets/bear/bird_flying.wings.bvh) byte for
# byte. Run by ctest: -DCUBTOOL= -DSRC= -DOUT= (a directory)
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${CUBTOOL} wings --assets ${SRC}/assets --out-dir ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE progress)
message("${summary}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cubtool wings failed (${rc}):\n${progress}")
endif()
foreach(f bear_winged.xml bird_flying.wings.bvh)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/${f} ${SRC}/assets/bear/${f}
                  RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "${OUT}/${f} differs from assets/bear/${f}: re-run `cubtool wings` "
                        "and look at why (docs/evolve.md, \"The winged bear\")")
  endif()
endforeach()
message("check_wings: cubtool wings reproduces assets/bear/bear_winged.xml and "
        "bird_flying.wings.bvh byte for byte")
