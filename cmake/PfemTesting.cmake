# One helper registers every test file: each tests/<label>/<name>_test.cpp becomes an
# executable whose GoogleTest cases are ctest tests carrying that label.
include(GoogleTest)
function(pfem_add_test_dir dir label)
  file(GLOB sources CONFIGURE_DEPENDS ${dir}/*_test.cpp)
  foreach(src ${sources})
    get_filename_component(name ${src} NAME_WE)
    add_executable(${name} ${src})
    target_link_libraries(${name} PRIVATE ${ARGN} GTest::gtest_main)
    target_compile_options(${name} PRIVATE ${PFEM_WARNINGS})
    target_compile_definitions(${name} PRIVATE
      PFEM_SOURCE_DIR="${CMAKE_SOURCE_DIR}" PFEM_BINARY_DIR="${CMAKE_BINARY_DIR}")
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
    gtest_discover_tests(${name} PROPERTIES LABELS ${label}
      WORKING_DIRECTORY ${CMAKE_BINARY_DIR} DISCOVERY_TIMEOUT 60)
  endforeach()
endfunction()
