# Writes OUTPUT, a header with every shader in SHADERS as a string constant
# named after its file: shaders/sphere_impostor.vert.glsl -> sphere_impostor_vert.
set(content "#pragma once\n// Generated from .glsl files by src/render/embed_shaders.cmake. Do not edit.\n#include <string_view>\nnamespace sph::shaders {\n")
foreach(file ${SHADERS})
    get_filename_component(name ${file} NAME)
    string(REGEX REPLACE "\\.glsl$" "" name ${name})
    string(REPLACE "." "_" name ${name})
    file(READ ${file} text)
    string(APPEND content "inline constexpr std::string_view ${name} = R\"sphclip_glsl(${text})sphclip_glsl\";\n")
endforeach()
string(APPEND content "}\n")
file(WRITE ${OUTPUT}.tmp "${content}")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
