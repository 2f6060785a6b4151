# Embeds text files (OpenCL sources, the report page) into a generated C++
# file at build time, so the binary needs no data files at run time, and
# writes a header declaring them. Both are rebuilt whenever a source changes.
#
#   mcquad_embed_sources(OUTPUT <cpp> HEADER <h> NAMESPACE <ns> SOURCES <files...>)
# defines, for each file, `const char* const <ns>::<name>` (the file name,
# dots becoming underscores: evolution.cl -> evolution_cl), declared in <h>.
# List <h> among the target's sources, so that it exists before its users
# are compiled, and put its folder on the include path.
function(mcquad_embed_sources)
  cmake_parse_arguments(ARG "" "OUTPUT;HEADER;NAMESPACE" "SOURCES" ${ARGN})
  get_filename_component(header_name ${ARG_HEADER} NAME)
  add_custom_command(
    OUTPUT ${ARG_OUTPUT} ${ARG_HEADER}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${ARG_OUTPUT} -DHEADER=${ARG_HEADER} -DHEADER_NAME=${header_name}
            -DNAMESPACE=${ARG_NAMESPACE} "-DSOURCES=${ARG_SOURCES}" -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_sources.cmake
    DEPENDS ${ARG_SOURCES} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/embed_sources.cmake
    COMMENT "Embedding ${header_name}"
    VERBATIM)
endfunction()
