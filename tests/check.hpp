// Tiny check macros for the CTest executables: each failed check prints where and why, and the
// test's exit code is the number of failures.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace check {

inline int& failures() {
  static int n = 0;
  return n;
}

inline void fail(const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "%s:%d: FAILED: %s\n", file, line, what.c_str());
  ++failures();
}

inline int result() {
  if (failures() == 0) std::printf("all checks passed\n");
  else std::printf("%d check(s) failed\n", failures());
  return failures() == 0 ? 0 : 1;
}

}  // namespace check

#define CHECK(cond)                                                \
  do {                                                             \
    if (!(cond)) check::fail(__FILE__, __LINE__, "CHECK(" #cond ")"); \
  } while (0)

// |a - b| <= tol
#define CHECK_NEAR(a, b, tol)                                                                             \
  do {                                                                                                    \
    const double check_a_ = (a), check_b_ = (b), check_t_ = (tol);                                        \
    if (!(std::abs(check_a_ - check_b_) <= check_t_)) {                                                   \
      char check_buf_[256];                                                                               \
      std::snprintf(check_buf_, sizeof check_buf_, "%s = %.10g, %s = %.10g, |diff| = %.3g > %.3g", #a,   \
                    check_a_, #b, check_b_, std::abs(check_a_ - check_b_), check_t_);                     \
      check::fail(__FILE__, __LINE__, check_buf_);                                                        \
    }                                                                                                     \
  } while (0)

// |a - b| <= rel |b|
#define CHECK_REL(a, b, rel)                                                                              \
  do {                                                                                                    \
    const double check_a_ = (a), check_b_ = (b), check_r_ = (rel);                                        \
    if (!(std::abs(check_a_ - check_b_) <= check_r_ * std::abs(check_b_))) {                             \
      char check_buf_[256];                                                                               \
      std::snprintf(check_buf_, sizeof check_buf_, "%s = %.10g, %s = %.10g, relative error %.3g > %.3g", \
                    #a, check_a_, #b, check_b_, std::abs(check_a_ - check_b_) / std::abs(check_b_),       \
                    check_r_);                                                                            \
      check::fail(__FILE__, __LINE__, check_buf_);                                                        \
    }                                                                                                     \
  } while (0)

// The expression throws an exception whose message contains every given fragment.
#define CHECK_THROWS_WITH(expr, ...)                                                                 \
  do {                                                                                               \
    bool check_threw_ = false;                                                                       \
    try {                                                                                            \
      (void)(expr);                                                                                  \
    } catch (const std::exception& check_e_) {                                                      \
      check_threw_ = true;                                                                           \
      const std::string check_msg_ = check_e_.what();                                                \
      for (const char* check_frag_ : {__VA_ARGS__})                                                  \
        if (check_msg_.find(check_frag_) == std::string::npos)                                       \
          check::fail(__FILE__, __LINE__,                                                            \
                      std::string("message '") + check_msg_ + "' lacks '" + check_frag_ + "'");     \
    }                                                                                                \
    if (!check_threw_) check::fail(__FILE__, __LINE__, "expected " #expr " to throw");             \
  } while (0)
