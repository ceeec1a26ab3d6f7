#pragma once
// Preprocessor iteration over a list of parenthesised tuples (up to 20), for the macros that
// expand the kernel list (engine/kernels/kernel_macros.h) and check the layouts (layout.h).
#define MASAV_PP_CAT(a, b) MASAV_PP_CAT_I(a, b)
#define MASAV_PP_CAT_I(a, b) a##b
#define MASAV_PP_COUNT(...)                                                                      \
  MASAV_PP_COUNT_I(__VA_ARGS__, 20, 19, 18, 17, 16, 15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, \
                   2, 1, 0)
#define MASAV_PP_COUNT_I(a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15, a16, \
                         a17, a18, a19, a20, n, ...)                                            \
  n
#define MASAV_PP_EXPAND(x) x
#define MASAV_PP_UNPAREN(...) __VA_ARGS__
// m(d, tuple's elements...) for one tuple (m is expanded once the tuple is opened).
#define MASAV_PP_PREPEND(d, x) (d, MASAV_PP_UNPAREN x)
#define MASAV_PP_APPLY(m, d, x) MASAV_PP_EXPAND(m MASAV_PP_PREPEND(d, x))

// m applied to each tuple with `d` first: MASAV_PP_EACH(m, d, (a, b), (c, e)) -> m(d, a, b)
// m(d, c, e).
#define MASAV_PP_EACH(m, d, ...) \
  MASAV_PP_CAT(MASAV_PP_EACH_, MASAV_PP_COUNT(__VA_ARGS__))(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_1(m, d, x) MASAV_PP_APPLY(m, d, x)
#define MASAV_PP_EACH_2(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_1(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_3(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_2(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_4(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_3(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_5(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_4(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_6(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_5(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_7(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_6(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_8(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_7(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_9(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_8(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_10(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_9(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_11(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_10(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_12(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_11(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_13(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_12(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_14(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_13(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_15(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_14(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_16(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_15(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_17(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_16(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_18(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_17(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_19(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_18(m, d, __VA_ARGS__)
#define MASAV_PP_EACH_20(m, d, x, ...) MASAV_PP_APPLY(m, d, x) MASAV_PP_EACH_19(m, d, __VA_ARGS__)
