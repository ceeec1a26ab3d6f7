# The library (include/masav/, examples/, the installed package, the API reference):
#  - library.example_*: each example run in the tree, at sizes that fit CI;
#  - library.install_consumer: `cmake --install` into a fresh prefix, then a separate ten-line
#    CMake project (examples/consumer) and the examples as their own project built against it
#    with find_package(masav), a pkg-config build, and every C++ snippet of docs/library.md
#    compiled and run against it;
#  - docs.api: Doxygen over include/masav/ with zero warnings (every public symbol documented).
if(NOT MASAV_BUILD_EXAMPLES)
  return()
endif()
set(ex ${CMAKE_BINARY_DIR}/examples)
set(ex_dir ${CMAKE_BINARY_DIR}/example_runs)
file(MAKE_DIRECTORY ${ex_dir})
add_test(NAME library.example_sort_backends COMMAND example_sort_backends 20000)
add_test(NAME library.example_dambreak_vtp
         COMMAND example_dambreak_vtp ${ex_dir}/dambreak.vtp 1500 0.5)
add_test(NAME library.example_atom_png COMMAND example_atom_png ${ex_dir}/atom.png state3 20000)
add_test(NAME library.example_compare_backends_test COMMAND example_compare_backends_test)
set_tests_properties(library.example_dambreak_vtp PROPERTIES
                     PASS_REGULAR_EXPRESSION "steps to t = 0.500 s")
set_tests_properties(library.example_atom_png PROPERTIES PASS_REGULAR_EXPRESSION "320x320 image")
# The example's own skip (a doctest MESSAGE: doctest has no run-time skip) is a skip to ctest,
# never a pass.
set_tests_properties(library.example_compare_backends_test PROPERTIES
                     SKIP_REGULAR_EXPRESSION "skipped: no Vulkan device")
foreach(t sort_backends dambreak_vtp atom_png compare_backends_test)
  set_tests_properties(library.example_${t} PROPERTIES LABELS library ENVIRONMENT "${test_env}"
                       WORKING_DIRECTORY ${ex_dir})
endforeach()

add_test(NAME library.install_consumer
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/install_consumer.sh ${CMAKE_BINARY_DIR}
                 ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR}/install_consumer)
set_tests_properties(library.install_consumer PROPERTIES LABELS library TIMEOUT 900
                     ENVIRONMENT "${test_env}" RUN_SERIAL TRUE)

configure_file(${PROJECT_SOURCE_DIR}/docs/api/Doxyfile.in ${CMAKE_BINARY_DIR}/api_docs/Doxyfile
               @ONLY)
add_test(NAME docs.api COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/api_docs.sh
                               ${CMAKE_BINARY_DIR}/api_docs/Doxyfile ${CMAKE_BINARY_DIR}/api_docs)
set_tests_properties(docs.api PROPERTIES LABELS library SKIP_RETURN_CODE 77)
