#include "check.h"

int main() {
  auto& r = dualight::test::Registry::get();
  int failed_tests = 0;
  for (const auto& [name, run] : r.tests) {
    const int before = r.failures;
    run();
    const bool ok = r.failures == before;
    failed_tests += ok ? 0 : 1;
    std::printf("%s %s\n", ok ? "PASS" : "FAIL", name.c_str());
  }
  std::printf("%zu passed, %d failed\n", r.tests.size() - failed_tests, failed_tests);
  return failed_tests == 0 ? 0 : 1;
}
