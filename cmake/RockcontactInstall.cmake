# `cmake --install`: the headers, the static libraries (kernel, contact, dynamics, generators),
# the `rockcontact` executable, the CMake package (find_package(rockcontact) ->
# rockcontact::rockcontact) and rockcontact.pc.
include(CMakePackageConfigHelpers)

# The one target a host links: dynamics, hence contact and kernel. Hosts know it as
# rockcontact::rockcontact; in this tree `rockcontact` is already the executable.
add_library(rockcontact_umbrella INTERFACE)
add_library(rockcontact::rockcontact ALIAS rockcontact_umbrella)
target_link_libraries(rockcontact_umbrella INTERFACE rockcontact_dynamics)

set_target_properties(rockcontact_kernel_core PROPERTIES EXPORT_NAME kernel_core)
set_target_properties(rockcontact_kernel2d PROPERTIES EXPORT_NAME kernel2d)
set_target_properties(rockcontact_kernel3d PROPERTIES EXPORT_NAME kernel3d)
set_target_properties(rockcontact_kernel PROPERTIES EXPORT_NAME kernel)
set_target_properties(rockcontact_contact PROPERTIES EXPORT_NAME contact)
set_target_properties(rockcontact_dynamics PROPERTIES EXPORT_NAME dynamics)
set_target_properties(rockcontact_umbrella PROPERTIES EXPORT_NAME rockcontact)
set_target_properties(rockcontact_generators PROPERTIES EXPORT_NAME generators)

install(TARGETS rockcontact_kernel_core rockcontact_kernel2d rockcontact_kernel3d rockcontact_kernel
  rockcontact_contact
  rockcontact_dynamics rockcontact_umbrella rockcontact_generators
  EXPORT rockcontactTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS rockcontact RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The paper scenes that `rockcontact validate` and `report` run, where the installed executable
# looks for them.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/scenes/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/rockcontact/scenes
  FILES_MATCHING PATTERN "*.json" PATTERN "README.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/scenes3d/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/rockcontact/scenes3d
  FILES_MATCHING PATTERN "*.json" PATTERN "README.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/scenes_cdem/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/rockcontact/scenes_cdem
  FILES_MATCHING PATTERN "*.json" PATTERN "README.md")

# contact/embed/include also holds the C API beside its rockcontact/ tree: rockcontact.h and its
# Fortran module rockcontact.f90, installed as source since .mod files are compiler-specific.
install(DIRECTORY
    ${PROJECT_SOURCE_DIR}/kernel/core/include/
    ${PROJECT_SOURCE_DIR}/kernel/2d/include/
    ${PROJECT_SOURCE_DIR}/kernel/3d/include/
    ${PROJECT_SOURCE_DIR}/contact/friction/include/
    ${PROJECT_SOURCE_DIR}/contact/potential2d/include/
    ${PROJECT_SOURCE_DIR}/contact/generalized3d/include/
    ${PROJECT_SOURCE_DIR}/contact/embed/include/
    ${PROJECT_SOURCE_DIR}/dynamics/dda2d/include/
    ${PROJECT_SOURCE_DIR}/dynamics/dda3d/include/
    ${PROJECT_SOURCE_DIR}/dynamics/cdem/include/
    ${PROJECT_SOURCE_DIR}/dynamics/io/include/
    ${PROJECT_SOURCE_DIR}/robustness_tests/generators/include/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h" PATTERN "*.f90")
install(FILES ${PROJECT_BINARY_DIR}/include/rockcontact/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rockcontact)

set(ROCKCONTACT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/rockcontact)
install(EXPORT rockcontactTargets
  NAMESPACE rockcontact::
  DESTINATION ${ROCKCONTACT_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/rockcontactConfig.cmake.in
  ${PROJECT_BINARY_DIR}/rockcontactConfig.cmake
  INSTALL_DESTINATION ${ROCKCONTACT_CMAKE_DIR})
# 0.x: a minor release may break the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rockcontactConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES
    ${PROJECT_BINARY_DIR}/rockcontactConfig.cmake
    ${PROJECT_BINARY_DIR}/rockcontactConfigVersion.cmake
  DESTINATION ${ROCKCONTACT_CMAKE_DIR})

# pkg-config, for hosts built without CMake. OpenMP's flag is the compiler's (dynamics/ found
# it in its own scope).
find_package(OpenMP REQUIRED)
file(RELATIVE_PATH ROCKCONTACT_PC_PREFIX
  ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" ROCKCONTACT_PC_PREFIX "${ROCKCONTACT_PC_PREFIX}")
set(ROCKCONTACT_PC_DEFINES "")
if(ROCKCONTACT_PREDICATE_STATS)
  set(ROCKCONTACT_PC_DEFINES " -DROCKCONTACT_PREDICATE_STATS=1")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/rockcontact.pc.in ${PROJECT_BINARY_DIR}/rockcontact.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/rockcontact.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

if(ROCKCONTACT_BUILD_TESTS)
  include(${CMAKE_CURRENT_LIST_DIR}/RockcontactInstallTests.cmake)
endif()
