# Build the fuzz corpus in the build tree: every input is a selector byte
# ('B' BVH, 'A' ASF+AMC, ... see fuzz_motion_parsers.c) then the text; ASF
# and AMC are joined by the marker fuzz_motion_parsers.c splits on. Seeds
# named *.fuzz already start with their selector byte ('X' character, 'Q'
# pack, 'K' keys) and are copied as they are. Real files come from the
# shared data when it is there (truncated by -max_len at run time).
file(MAKE_DIRECTORY ${OUT})
file(GLOB ready_seeds ${SEEDS}/*.fuzz)
file(COPY ${ready_seeds} DESTINATION ${OUT})
set(MARK "\n==AMC==\n")
file(GLOB bvh_seeds ${SEEDS}/*.bvh)
foreach(f ${bvh_seeds})
  get_filename_component(n ${f} NAME_WE)
  file(READ ${f} text)
  file(WRITE ${OUT}/seed_${n}_bvh "B${text}")
endforeach()
file(GLOB asf_seeds ${SEEDS}/*.asf)
foreach(f ${asf_seeds})
  get_filename_component(n ${f} NAME_WE)
  file(READ ${f} asf)
  file(READ ${SEEDS}/${n}.amc amc)
  file(WRITE ${OUT}/seed_${n}_asfamc "A${asf}${MARK}${amc}")
endforeach()
foreach(f animdraw/cmu1/jumping_jacks.bvh dog/D1_010_KAN01_002.bvh
          bandai/data/dataset-1_byebye_angry_001.bvh cmu/daz43/08_01.bvh)
  if(EXISTS ${DATA}/${f})
    get_filename_component(n ${f} NAME_WE)
    file(READ ${DATA}/${f} text LIMIT 16000)
    file(WRITE ${OUT}/real_${n}_bvh "B${text}")
  endif()
endforeach()
if(EXISTS ${DATA}/cmu/asfamc/02.asf)
  file(READ ${DATA}/cmu/asfamc/02.asf asf)
  file(READ ${DATA}/cmu/asfamc/02_02.amc amc LIMIT 8000)
  file(WRITE ${OUT}/real_02_02_asfamc "A${asf}${MARK}${amc}")
endif()
