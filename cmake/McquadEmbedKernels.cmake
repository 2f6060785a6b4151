# Embeds OpenCL sources into a generated C++ file at build time, so the binary
# needs no kernel files at run time. The generated file is rebuilt whenever a
# source changes.
#
#   mcquad_embed_sources(OUTPUT <cpp> NAMESPACE <ns> SOURCES <files...>)
# defines, for each file, `const char* <ns>::<stem>_source` (dots become underscores).
function(mcquad_embed_sources)
  cmake_parse_arguments(ARG "" "OUTPUT;NAMESPACE" "SOURCES" ${ARGN})
  add_custom_command(
    OUTPUT ${ARG_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} -DNAMESPACE=${ARG_NAMESPACE}
            "-DSOURCES=${ARG_SOURCES}" -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_sources.cmake
    DEPENDS ${ARG_SOURCES} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_sources.cmake
    COMMENT "Embedding OpenCL sources"
    VERBATIM)
endfunction()
