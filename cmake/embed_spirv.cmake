# cmake -DSPV=<file.spv> -DNAME=<symbol> -DOUT=<file.cpp> -P embed_spirv.cmake
# Writes the SPIR-V words as a C++ array (little-endian words, as glslc emits them).
file(READ "${SPV}" hex HEX)
string(LENGTH "${hex}" len)
math(EXPR rem "${len} % 8")
if(NOT rem EQUAL 0 OR len EQUAL 0)
  message(FATAL_ERROR "${SPV} is not a whole number of 32-bit words")
endif()
string(REGEX REPLACE "([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])"
       "0x\\4\\3\\2\\1u," words "${hex}")
math(EXPR count "${len} / 8")
file(WRITE "${OUT}.tmp"
  "// Generated from ${SPV} by cmake/embed_spirv.cmake. Do not edit.\n"
  "#include <cstddef>\n#include <cstdint>\n"
  "namespace masav::shaders {\n"
  "extern const uint32_t spv_${NAME}[] = {${words}};\n"
  "extern const size_t spv_${NAME}_words = ${count};\n"
  "}\n")
file(RENAME "${OUT}.tmp" "${OUT}")
