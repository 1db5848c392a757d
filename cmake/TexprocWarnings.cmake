# One place for the warning flags every texproc target uses.
# TEXPROC_WERROR=ON (CI) turns every warning into an error.
option(TEXPROC_WERROR "Treat compiler warnings as errors" OFF)

function(texproc_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wno-unused-parameter
    # Scalar references and SIMD twins must give identical bytes: never let the
    # compiler fuse a*b+c into an FMA behind our back.
    -ffp-contract=off)
  if(TEXPROC_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
