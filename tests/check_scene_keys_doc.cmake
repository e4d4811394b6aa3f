# Fails when docs/scene-keys.md is not what `sphclip keys --markdown` prints:
# the key table is generated from the keys the components declare.
# Usage: cmake -DSPHCLIP=path/to/sphclip -DDOC=docs/scene-keys.md -P check_scene_keys_doc.cmake
execute_process(COMMAND ${SPHCLIP} keys --markdown OUTPUT_VARIABLE generated RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "sphclip keys --markdown failed (exit ${status})")
endif()
file(READ ${DOC} committed)
if(NOT generated STREQUAL committed)
    message(FATAL_ERROR "docs/scene-keys.md is stale: regenerate it with\n"
                        "  build/sphclip keys --markdown > docs/scene-keys.md")
endif()
