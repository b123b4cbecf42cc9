# Warnings for steadylight's own code, as an INTERFACE target that every target links.
add_library(steadylight_warnings INTERFACE)
target_compile_options(steadylight_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wno-missing-field-initializers>)
