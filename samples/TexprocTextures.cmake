# texproc_add_textures(): cook textures with texproc as part of a CMake build.
#
#   include(TexprocTextures.cmake)
#   texproc_add_textures(albedo
#     COMMAND compress               # any texproc command that reads one file and writes one
#     INPUTS textures/a.png textures/b.png
#     OUTPUT_DIR ${CMAKE_CURRENT_BINARY_DIR}/cooked
#     SUFFIX .dds                 # output name: OUTPUT_DIR/<input stem>SUFFIX
#     OPTIONS --format bc1 --mips)
#
# Adds a target (built by `all`) with one custom command per input. Each
# command writes a depfile (texproc --depfile), so the Ninja and Makefile
# generators rebuild a texture when its input or the OpenColorIO config it
# used changes, and only then. --write-if-changed keeps an unchanged
# output's time stamp. TEXPROC_EXECUTABLE names the texproc program (found on
# PATH unless set). Needs CMake 3.20 (DEPFILE with Makefile generators).
cmake_minimum_required(VERSION 3.20)

if(NOT TEXPROC_EXECUTABLE)
  find_program(TEXPROC_EXECUTABLE texproc REQUIRED)
endif()

function(texproc_add_textures target)
  cmake_parse_arguments(PARSE_ARGV 1 TT "" "COMMAND;OUTPUT_DIR;SUFFIX" "INPUTS;OPTIONS")
  foreach(required COMMAND OUTPUT_DIR SUFFIX INPUTS)
    if(NOT TT_${required})
      message(FATAL_ERROR "texproc_add_textures(${target}): ${required} is required")
    endif()
  endforeach()
  set(outputs)
  foreach(input IN LISTS TT_INPUTS)
    get_filename_component(input "${input}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_filename_component(stem "${input}" NAME_WE)
    set(output "${TT_OUTPUT_DIR}/${stem}${TT_SUFFIX}")
    add_custom_command(
      OUTPUT "${output}"
      COMMAND "${TEXPROC_EXECUTABLE}" ${TT_COMMAND} "${input}" -o "${output}" ${TT_OPTIONS}
              -q --write-if-changed --depfile "${output}.d"
      DEPENDS "${input}"
      DEPFILE "${output}.d"
      COMMENT "texproc ${TT_COMMAND} ${stem}${TT_SUFFIX}"
      VERBATIM)
    list(APPEND outputs "${output}")
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${outputs})
endfunction()
