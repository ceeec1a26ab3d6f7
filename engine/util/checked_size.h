#pragma once
// Size arithmetic for everything read from a file: counts, extents and byte sizes are parsed as
// whole 64-bit integers and combined with overflow reported, naming the field, so that a declared
// size of 2^32 + 16 is refused instead of wrapping to 16.
#include <cstdint>
#include <string_view>

namespace masav {

// a + b and a * b, or an Error "<where>: invalid <field> = ..." when the result passes 2^64 - 1.
uint64_t checked_add(uint64_t a, uint64_t b, std::string_view where, std::string_view field);
uint64_t checked_mul(uint64_t a, uint64_t b, std::string_view where, std::string_view field);

// The whole of `text` (surrounding blanks allowed) as a decimal integer: no sign for the
// unsigned one, no fraction, no exponent, nothing that does not fit 64 bits.
uint64_t parse_u64(std::string_view text, std::string_view where, std::string_view field);
int64_t parse_i64(std::string_view text, std::string_view where, std::string_view field);

// v when it lies in [lo, hi] (so it fits 32 bits when hi does), else an Error naming the range.
uint32_t checked_u32_in(uint64_t v, uint32_t lo, uint32_t hi, std::string_view where,
                        std::string_view field);

}  // namespace masav
