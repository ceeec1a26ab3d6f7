# Per-target defaults (never global CMAKE_CXX_FLAGS edits).
function(masav_target_defaults target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>
    # Two roundings for a*b+c on the CPU, as GLSL `precise` and CUDA __fmul_rn/__fadd_rn give:
    # the integer kernels (grid cells, neighbour counts) must agree bit for bit across backends.
    $<$<COMPILE_LANGUAGE:CXX>:-ffp-contract=off>
    $<$<COMPILE_LANGUAGE:CUDA>:--expt-relaxed-constexpr -Xcompiler=-Wall>)
endfunction()
