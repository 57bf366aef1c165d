# The fuzz targets' runs, as tests of the main build (included by the top-level CMakeLists.txt
# when PFEM_FUZZ is off). Fixture fuzz_build keeps their clang++-14 build in build/fuzz
# current (scripts/build-fuzz; scripts/build makes it first); then each target runs 5 s in
# the default run and 60 s under the label slow (fuzz/run-target). Without clang++-14 there
# are no fuzz tests.
find_program(PFEM_CLANGXX clang++-14)
if(NOT PFEM_CLANGXX)
  message(STATUS "fuzz: clang++-14 not found; no fuzz tests (scripts/install-deps installs it)")
  return()
endif()
set(fuzz_dir ${CMAKE_BINARY_DIR}/fuzz)
add_test(NAME fuzz_build COMMAND ${CMAKE_SOURCE_DIR}/scripts/build-fuzz ${fuzz_dir})
set_tests_properties(fuzz_build PROPERTIES FIXTURES_SETUP fuzz_build LABELS fuzz TIMEOUT 3600
  RUN_SERIAL ON)
foreach(target model problem request)
  add_test(NAME fuzz_${target} COMMAND ${CMAKE_SOURCE_DIR}/fuzz/run-target ${fuzz_dir} ${target} 5)
  add_test(NAME fuzz_${target}_60s
    COMMAND ${CMAKE_SOURCE_DIR}/fuzz/run-target ${fuzz_dir} ${target} 60)
  set_tests_properties(fuzz_${target} PROPERTIES FIXTURES_REQUIRED fuzz_build LABELS fuzz
    TIMEOUT 300)
  set_tests_properties(fuzz_${target}_60s PROPERTIES FIXTURES_REQUIRED fuzz_build
    LABELS "fuzz;slow" TIMEOUT 600)
endforeach()
