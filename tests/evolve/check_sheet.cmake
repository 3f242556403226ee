# `cubtool evolve --sheet` writes one contact sheet: parent 1, parent 2 and
# the child side by side (4 frames each: 3 x 4 x 200 px wide, a 24 px title
# strip and two 240 px rows high), and no separate parent sheets. The pair
# is the shipped winged bear's (bird_flying x our bird). Run by ctest:
# -DCUBTOOL= -DSRC= -DOUT= (a directory)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${CUBTOOL} evolve ${SRC}/assets/clips/bear.cubclips:bird_flying
                        ${SRC}/assets/bird/bird.xml:${SRC}/assets/keys/bird_flap.keys
                        --character1 ${SRC}/assets/bear/bear.xml --out ${OUT}/child.bvh
                        --sheet ${OUT}/sheet.png
                RESULT_VARIABLE rc OUTPUT_VARIABLE summary ERROR_VARIABLE progress)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cubtool evolve --sheet failed (${rc}):\n${progress}")
endif()
if(NOT EXISTS ${OUT}/sheet.png)
  message(FATAL_ERROR "no ${OUT}/sheet.png")
endif()
file(GLOB extra ${OUT}/sheet_*.png)
if(extra)
  message(FATAL_ERROR "separate sheets written: ${extra}")
endif()
# The PNG signature, then IHDR: width and height, big-endian, at bytes 16-23.
file(READ ${OUT}/sheet.png sig LIMIT 8 HEX)
file(READ ${OUT}/sheet.png ihdr OFFSET 16 LIMIT 8 HEX)
if(NOT sig STREQUAL "89504e470d0a1a0a")
  message(FATAL_ERROR "${OUT}/sheet.png is not a PNG (${sig})")
endif()
string(SUBSTRING ${ihdr} 0 8 w)
string(SUBSTRING ${ihdr} 8 8 h)
math(EXPR w "0x${w}")
math(EXPR h "0x${h}")
if(NOT w EQUAL 2400 OR NOT h EQUAL 504)
  message(FATAL_ERROR "sheet.png is ${w} x ${h}, not 2400 x 504 (3 clips x 4 frames)")
endif()
message("check_sheet: one contact sheet, ${w} x ${h}: parent 1, parent 2, child")
