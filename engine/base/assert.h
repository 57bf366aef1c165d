#pragma once
// PFEM_ASSERT(condition, message): a check of an internal invariant (something the code
// itself guarantees, never user or wire input: that is validated always, with a FieldError).
// In debug builds a broken invariant prints where and why and aborts; with NDEBUG (Release)
// the condition is not evaluated. Not for hot loops.
#include <cstdio>
#include <cstdlib>

namespace pfem::detail {
[[noreturn]] inline void assertion_failed(const char* condition, const char* message, const char* file,
                                          int line) {
  std::fprintf(stderr, "%s:%d: internal invariant broken: %s (%s)\n", file, line, message, condition);
  std::abort();
}
}  // namespace pfem::detail

#ifdef NDEBUG
#define PFEM_ASSERT(condition, message) static_cast<void>(sizeof(static_cast<bool>(condition)))
#else
#define PFEM_ASSERT(condition, message) \
  ((condition) ? static_cast<void>(0) : ::pfem::detail::assertion_failed(#condition, message, __FILE__, __LINE__))
#endif
