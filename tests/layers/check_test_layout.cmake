# Fails when the tests stop mirroring the sources: every C++ test lies in
# tests/<folder>/ where <folder> is a folder of host/ (or kernels, cli), so
# the tests of host/mesh/ are found in tests/mesh/.
#   cmake -DROOT=<repository root> -P tests/layers/check_test_layout.cmake
if(NOT ROOT)
  message(FATAL_ERROR "usage: cmake -DROOT=<repository root> -P check_test_layout.cmake")
endif()
file(GLOB source_folders LIST_DIRECTORIES true RELATIVE "${ROOT}/host" "${ROOT}/host/*")
list(APPEND source_folders kernels cli)
file(GLOB_RECURSE tests RELATIVE "${ROOT}/tests" "${ROOT}/tests/*_test.cpp" "${ROOT}/tests/*_test.sh")
set(misplaced 0)
foreach(test IN LISTS tests)
  get_filename_component(folder "${test}" DIRECTORY)
  list(FIND source_folders "${folder}" found)
  if(found EQUAL -1)
    message(SEND_ERROR "tests/${test}: not in a folder named after a source folder (${source_folders})")
    math(EXPR misplaced "${misplaced} + 1")
  endif()
endforeach()
if(misplaced GREATER 0)
  message(FATAL_ERROR "${misplaced} test file(s) outside the source folders' mirror")
endif()
list(LENGTH tests count)
message(STATUS "${count} test files mirror the source folders")
