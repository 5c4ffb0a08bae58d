// A minimal test harness: CHECK records failures with file and line; main() reports them.
#pragma once
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace dualight::test {

struct Registry {
  std::vector<std::pair<std::string, std::function<void()>>> tests;
  int failures = 0;
  static Registry& get() {
    static Registry r;
    return r;
  }
};

struct Register {
  Register(const char* name, std::function<void()> f) { Registry::get().tests.emplace_back(name, std::move(f)); }
};

}  // namespace dualight::test

#define TEST_CASE(name)                                                               \
  static void name();                                                                 \
  static const dualight::test::Register register_##name(#name, name);                 \
  static void name()

#define CHECK(cond)                                                                   \
  do {                                                                                \
    if (!(cond)) {                                                                    \
      std::printf("  %s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond);         \
      ++dualight::test::Registry::get().failures;                                     \
    }                                                                                 \
  } while (0)

#define CHECK_NEAR(a, b, tol) CHECK(std::abs((a) - (b)) <= (tol))
