# Compiler settings shared by every rockcontact target.
add_library(rockcontact_options INTERFACE)
target_compile_options(rockcontact_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  # The predicate filters carry error bounds derived for correctly rounded
  # IEEE operations; a fused multiply-add would silently break them.
  -ffp-contract=off -fno-fast-math)
if(ROCKCONTACT_PREDICATE_STATS)
  target_compile_definitions(rockcontact_options INTERFACE ROCKCONTACT_PREDICATE_STATS=1)
endif()
if(ROCKCONTACT_SANITIZE)
  target_compile_options(rockcontact_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(rockcontact_options INTERFACE -fsanitize=address,undefined)
endif()
