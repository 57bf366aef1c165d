# pfem_add_test(<name> <label> <libraries...>): tests/<label>/<name>.cpp becomes an
# executable whose GoogleTest cases are ctest tests carrying <label> (unit, integration, slow).
include(GoogleTest)
function(pfem_add_test name label)
  add_executable(${name} ${CMAKE_SOURCE_DIR}/tests/${label}/${name}.cpp)
  target_link_libraries(${name} PRIVATE ${ARGN} GTest::gtest_main)
  target_compile_options(${name} PRIVATE ${PFEM_WARNINGS})
  target_compile_definitions(${name} PRIVATE
    PFEM_SOURCE_DIR="${CMAKE_SOURCE_DIR}" PFEM_BINARY_DIR="${CMAKE_BINARY_DIR}")
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  gtest_discover_tests(${name} PROPERTIES LABELS ${label}
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR} DISCOVERY_TIMEOUT 60)
endfunction()
