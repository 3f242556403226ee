# `cubtool tag` on the shipped library reproduces the committed tag file
# byte for byte. Run by ctest: -DCUBTOOL= -DSRC= -DOUT=
if(NOT EXISTS ${SRC}/assets/clips/bear.cubclips)
  message("check_tags: no assets/clips/bear.cubclips yet; nothing to compare")
  return()
endif()
execute_process(COMMAND ${CUBTOOL} tag --library ${SRC}/assets/clips/bear.cubclips
                        --character ${SRC}/assets/bear/bear.xml --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE progress)
message("${summary}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cubtool tag failed (${rc}):\n${progress}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${SRC}/assets/clips/bear.tags.xml
                RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "${OUT} differs from assets/clips/bear.tags.xml: re-run "
                      "`cubtool tag --out assets/clips/bear.tags.xml` and look at why")
endif()
message("check_tags: cubtool tag reproduces assets/clips/bear.tags.xml byte for byte")
