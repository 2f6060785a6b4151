# Per-target compiler settings: warnings (errors in CI) and optional sanitizers.
function(mcquad_target_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                             -Wno-deprecated-declarations
                                             # GCC 12 false positives inside OpenMesh property containers
                                             $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
    # Position-independent code (CMakeLists.txt) without ELF's symbol
    # interposition, which would stop GCC inlining the library's own
    # functions into each other: nothing replaces them at run time.
    target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
    if(MCQUAD_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
    if(MCQUAD_SANITIZERS)
      target_compile_options(${target} PRIVATE -fsanitize=${MCQUAD_SANITIZERS} -fno-omit-frame-pointer)
      target_link_options(${target} PRIVATE -fsanitize=${MCQUAD_SANITIZERS})
    endif()
  endif()
endfunction()
