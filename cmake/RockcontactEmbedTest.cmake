# cmake -DMODE=install|cmake|pkgconfig ... -P RockcontactEmbedTest.cmake (from
# RockcontactInstallTests.cmake). Any failing step fails the test.
#   install    the build tree into PREFIX, from scratch, so files the tree no longer has do not
#              survive from an earlier run; the package must not name the source or build tree
#   cmake      examples/embed as its own project, finding rockcontact in PREFIX only; runs its
#              hosts
#   pkgconfig  examples/embed/dem_host.cpp with `pkg-config --static --cflags --libs`; runs it
cmake_minimum_required(VERSION 3.25)
set(embed ${SOURCE_DIR}/examples/embed)

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
    COMMAND_ERROR_IS_FATAL ANY)
  file(GLOB_RECURSE package_files ${PREFIX}/*.cmake ${PREFIX}/*.pc)
  foreach(file IN LISTS package_files)
    file(READ ${file} text)
    foreach(tree ${SOURCE_DIR} ${BUILD_DIR})
      string(FIND "${text}" "${tree}" at)
      if(at GREATER -1)
        message(FATAL_ERROR "${file} names ${tree}: the installed package is not self-contained")
      endif()
    endforeach()
  endforeach()

elseif(MODE STREQUAL "cmake")
  file(REMOVE_RECURSE ${WORK})
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${embed} -B ${WORK} -G ${GENERATOR}
      -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release
      -DCMAKE_CXX_FLAGS=${HOST_FLAGS} -DCMAKE_PREFIX_PATH=${PREFIX}
      -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
    COMMAND_ECHO STDOUT COMMAND_ERROR_IS_FATAL ANY)
  # A package found anywhere else (another install, an environment CMAKE_PREFIX_PATH) would
  # make a pass meaningless.
  file(STRINGS ${WORK}/CMakeCache.txt found REGEX "^rockcontact_DIR:")
  string(REGEX REPLACE "^[^=]*=" "" found "${found}")
  cmake_path(IS_PREFIX PREFIX "${found}" NORMALIZE inside)
  if(NOT inside)
    message(FATAL_ERROR "rockcontact found in '${found}', not in ${PREFIX}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} COMMAND_ERROR_IS_FATAL ANY)
  execute_process(COMMAND ${WORK}/dem_host COMMAND_ERROR_IS_FATAL ANY)
  execute_process(COMMAND ${WORK}/sliding_host COMMAND_ERROR_IS_FATAL ANY)

elseif(MODE STREQUAL "pkgconfig")
  file(REMOVE_RECURSE ${WORK})
  file(MAKE_DIRECTORY ${WORK})
  set(ENV{PKG_CONFIG_PATH} ${PREFIX}/${LIBDIR}/pkgconfig)
  execute_process(COMMAND ${PKG_CONFIG} --static --cflags --libs rockcontact
    OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE COMMAND_ERROR_IS_FATAL ANY)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  separate_arguments(host_flags UNIX_COMMAND "${HOST_FLAGS}")
  execute_process(COMMAND ${CXX} ${host_flags} ${embed}/dem_host.cpp -o ${WORK}/dem_host ${flags}
    COMMAND_ECHO STDOUT COMMAND_ERROR_IS_FATAL ANY)
  execute_process(COMMAND ${WORK}/dem_host COMMAND_ERROR_IS_FATAL ANY)

else()
  message(FATAL_ERROR "MODE must be install, cmake or pkgconfig (got '${MODE}')")
endif()
