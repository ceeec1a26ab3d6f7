// Digit of a key for one LSD radix pass (engine/kernels/radix.h).
uint radix_digit(uint key, uint shift, uint bits) { return (key >> shift) & ((1u << bits) - 1u); }
