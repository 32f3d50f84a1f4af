#pragma once
// Invariant checks. A failed check is a programming error, not bad input: it prints where
// and why, then aborts (bad input is reported through return values and counters instead).
//
// STEREOSCOUT_CHECK is always on. STEREOSCOUT_DEBUG_CHECK follows assert(): on unless NDEBUG,
// and every preset we ship (release included) keeps asserts on.

namespace stereoscout::core {
[[noreturn]] void check_failed(const char* file, int line, const char* condition, const char* message);
}  // namespace stereoscout::core

#define STEREOSCOUT_CHECK(condition, message)                                              \
  do {                                                                                     \
    if (!(condition)) {                                                                    \
      ::stereoscout::core::check_failed(__FILE__, __LINE__, #condition, (message));        \
    }                                                                                      \
  } while (false)

#ifdef NDEBUG
#define STEREOSCOUT_DEBUG_CHECK(condition, message) \
  do {                                              \
    (void)sizeof(condition);                        \
  } while (false)
#else
#define STEREOSCOUT_DEBUG_CHECK(condition, message) STEREOSCOUT_CHECK(condition, message)
#endif
