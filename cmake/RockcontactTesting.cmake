# rockcontact_add_test(NAME SOURCES... [LIBS ...] [CGAL])
# One Boost.Test executable per concept, registered with CTest. Boost.Test is linked
# as a shared library (BOOST_TEST_DYN_LINK) so no test recompiles the framework.
function(rockcontact_add_test name)
  cmake_parse_arguments(ARG "CGAL" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} rockcontact_options
    Boost::unit_test_framework)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/robustness_tests/support)
  target_compile_definitions(${name} PRIVATE BOOST_TEST_DYN_LINK
    ROCKCONTACT_TESTDATA_DIR="${PROJECT_SOURCE_DIR}/robustness_tests/data"
    ROCKCONTACT_EXAMPLES_DIR="${PROJECT_SOURCE_DIR}/examples")
  if(ARG_CGAL)
    target_link_libraries(${name} PRIVATE CGAL::CGAL)
    if(ROCKCONTACT_SANITIZE)
      # CGAL's arrangement iterators (used by its Boolean operations) downcast a face base to
      # the face type in a way UBSan's vptr check reports although it is CGAL-internal and
      # well defined in practice; every other check stays on for these tests. (A source
      # property, because it must follow -fsanitize=undefined on the command line.)
      set_source_files_properties(${ARG_SOURCES} PROPERTIES COMPILE_OPTIONS -fno-sanitize=vptr)
    endif()
  endif()
  add_test(NAME ${name} COMMAND ${name} --log_level=message --report_level=short)
  # ctest -j runs tests side by side on few cores: an OpenMP thread that spins while it waits
  # for a busy core made a 221-block drop 6 times slower; passive waiting yields the core.
  set_tests_properties(${name} PROPERTIES ENVIRONMENT OMP_WAIT_POLICY=PASSIVE)
endfunction()
