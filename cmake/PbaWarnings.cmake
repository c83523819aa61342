# One place for compile flags shared by every pba target.
add_library(pba_flags INTERFACE)
target_compile_options(pba_flags INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>
  # & and | on bools are how the swarm's loops test without branches (collision_rules.hpp).
  $<$<CXX_COMPILER_ID:Clang>:-Wno-bitwise-instead-of-logical>
  $<$<BOOL:${PBA_WARNINGS_AS_ERRORS}>:-Werror>
  $<$<BOOL:${PBA_NATIVE}>:-march=native>)
