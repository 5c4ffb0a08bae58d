// The C++ unit tests' one include: doctest (TEST_CASE, CHECK, ...) and CHECK_NEAR, the absolute
// tolerance check the tests are written in (|a - b| <= tol, the values shown when it fails).
// ctest runs each TEST_CASE as its own test (doctest_discover_tests in CMakeLists.txt).
#pragma once
#include <cmath>

#include <doctest/doctest.h>

#define CHECK_NEAR(a, b, tol) CHECK(std::abs((a) - (b)) <= (tol))
