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

  # The installed executable finds its own scenes from another directory: `validate --quick`
  # passes and says it read them from PREFIX/share/rockcontact/scenes, not from the source tree.
  # Not in the sanitizer build, for the reason dynamics_cli_validate_quick is not.
  if(NOT ROCKCONTACT_SANITIZE)
    set(elsewhere ${PROJECT_BINARY_DIR}/installed-validate)
    file(MAKE_DIRECTORY ${elsewhere})
    add_test(NAME installed_validate_quick
      COMMAND ${CMAKE_COMMAND} -DEXE=${prefix}/${CMAKE_INSTALL_BINDIR}/rockcontact -DEXPECT_EXIT=0
        -DARG_COUNT=2 -DARG0=validate -DARG1=--quick
        "-DSTDOUT_REGEX=scenes from ${prefix}/${CMAKE_INSTALL_DATADIR}/rockcontact/scenes.*30 checks, 0 failed"
        -P ${PROJECT_SOURCE_DIR}/dynamics/tests/check_cli.cmake
      WORKING_DIRECTORY ${elsewhere})
    set_tests_properties(installed_validate_quick PROPERTIES FIXTURES_REQUIRED rockcontact_installed)
  endif()
endblock()
