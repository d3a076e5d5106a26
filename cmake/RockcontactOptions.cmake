# Compiler settings shared by every rockcontact target, in this build only: the libraries link
# it through $<BUILD_INTERFACE>, so an installed package does not impose our warnings, FP flags
# or sanitizers on its hosts (ROCKCONTACT_PREDICATE_STATS, which headers read, is on the kernel).
add_library(rockcontact_options INTERFACE)
# C and C++ only: the Fortran test of the C API compiles with gfortran, which rejects
# -Wno-sign-conversion and would warn about the rest.
target_compile_options(rockcontact_options INTERFACE
  "$<$<COMPILE_LANGUAGE:C,CXX>:-Wall;-Wextra;-Wpedantic;-Wshadow;-Wconversion;-Wno-sign-conversion>"
  # The predicate filters carry error bounds derived for correctly rounded
  # IEEE operations; a fused multiply-add would silently break them.
  -ffp-contract=off -fno-fast-math)
if(ROCKCONTACT_SANITIZE)
  target_compile_options(rockcontact_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(rockcontact_options INTERFACE -fsanitize=address,undefined)
endif()
