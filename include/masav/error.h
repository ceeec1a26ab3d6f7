#pragma once
/// \file
/// Errors. Everything masav refuses or fails at is thrown as one type, `masav::Error` (a
/// `std::runtime_error`), whose `what()` is the message the command line prints: where it
/// happened (backend and kernel, or the input field), what went wrong and what to do, e.g.
/// `masav.Sph: invalid particles = 0 (remedy: particles must be at least 1)`. Its parts are
/// `backend()`, `kernel()`, `problem()` and `remedy()`. A bad input is refused before any work
/// starts, naming the field, the value and the allowed range.
#include "engine/core/error.h"
