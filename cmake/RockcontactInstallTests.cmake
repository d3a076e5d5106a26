# The installed package as a host sees it: install into the build tree at test time (after the
# build), then build and run examples/embed against that prefix alone, once through its own
# CMake project and once through pkg-config. Steps in RockcontactEmbedTest.cmake.
block()
  set(prefix ${PROJECT_BINARY_DIR}/test-install)
  set(script ${CMAKE_CURRENT_LIST_DIR}/RockcontactEmbedTest.cmake)
  set(common -DPREFIX=${prefix} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DBUILD_DIR=${PROJECT_BINARY_DIR})

  # The sanitizer flags are not exported (rockcontact_options is build-only), but instrumented
  # libraries need the sanitizer runtime at link time: hosts get the flags the libraries were
  # linked with.
  set(host_flags "")
  if(ROCKCONTACT_SANITIZE)
    get_target_property(host_flags rockcontact_options INTERFACE_LINK_OPTIONS)
    list(JOIN host_flags " " host_flags)
  endif()
  set(host -DCXX=${CMAKE_CXX_COMPILER} "-DHOST_FLAGS=${host_flags}")

  add_test(NAME install_package COMMAND ${CMAKE_COMMAND} -DMODE=install ${common} -P ${script})
  set_tests_properties(install_package PROPERTIES FIXTURES_SETUP rockcontact_installed)

  add_test(NAME embed_host_installed COMMAND ${CMAKE_COMMAND} -DMODE=cmake ${common} ${host}
    -DGENERATOR=${CMAKE_GENERATOR} -DMAKE_PROGRAM=${CMAKE_MAKE_PROGRAM}
    -DWORK=${PROJECT_BINARY_DIR}/embed-host-cmake -P ${script})
  add_test(NAME embed_host_pkgconfig COMMAND ${CMAKE_COMMAND} -DMODE=pkgconfig ${common} ${host}
    -DPKG_CONFIG=${PKG_CONFIG_EXECUTABLE} -DLIBDIR=${CMAKE_INSTALL_LIBDIR}
    -DWORK=${PROJECT_BINARY_DIR}/embed-host-pkgconfig -P ${script})
  set_tests_properties(embed_host_installed embed_host_pkgconfig PROPERTIES
    FIXTURES_REQUIRED rockcontact_installed)
endblock()
