# The voice pack: `cubtool voice` asks words.c for every phrase the box can
# show for the shipped songs and speaks each with espeak-ng (Debian's,
# installed by scripts/setup.sh) at build time. Rendering here rather than
# committing the samples keeps the repository free of a 2 MB binary that
# every new phrase would change; espeak-ng 1.51 gives the same bytes on
# every run, and the box's event log never depends on them (docs/speech.md).
# Without espeak-ng the build goes on: the box then shows its words without
# speaking them (a warning at start), and the speech tests skip.
include(GNUInstallDirs)
find_program(CUB_ESPEAK_NG espeak-ng)
if(NOT CUB_ESPEAK_NG)
  message(WARNING "espeak-ng not found: the box will show its words but not speak them "
                  "(scripts/setup.sh installs it)")
  return()
endif()
file(GLOB CUB_VOICE_SONGS CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/assets/songs/*.song.xml)
get_filename_component(voice_dir ${CUB_VOICE_FILE} DIRECTORY)
add_custom_command(
  OUTPUT ${CUB_VOICE_FILE}
  COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0
          $<TARGET_FILE:cubtool> voice --espeak ${CUB_ESPEAK_NG} --out ${CUB_VOICE_FILE}
          --work ${voice_dir}/phrases --library ${CMAKE_SOURCE_DIR}/assets/clips/bear.cubclips
          ${CUB_VOICE_SONGS}
  DEPENDS cubtool ${CUB_VOICE_SONGS} ${CMAKE_SOURCE_DIR}/assets/clips/bear.cubclips
  COMMENT "Speaking the bear's words with espeak-ng"
  VERBATIM)
add_custom_target(cub_voice ALL DEPENDS ${CUB_VOICE_FILE})
install(FILES ${CUB_VOICE_FILE} DESTINATION ${CMAKE_INSTALL_DATADIR}/cubdance/voice)
