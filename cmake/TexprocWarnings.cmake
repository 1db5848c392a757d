# One place for the warning flags every texproc target uses.
function(texproc_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wno-unused-parameter -Wno-sign-compare
    # Scalar references and SIMD twins must give identical bytes: never let the
    # compiler fuse a*b+c into an FMA behind our back.
    -ffp-contract=off)
endfunction()
