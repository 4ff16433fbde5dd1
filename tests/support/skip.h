#pragma once
// A test whose data is missing is reported skipped, never passed. ISODEL_SKIP(reason) says why
// (Catch2's WARN) and ends the test case; when every test case a run executed ended this way,
// the test executable exits with kSkipReturnCode, which CTest reports as "Skipped"
// (SKIP_RETURN_CODE in tests/CMakeLists.txt). A run in which some cases ran and others skipped
// reports its real result: what ran must pass.
#include <catch2/catch.hpp>

namespace isodel::testing {

constexpr int kSkipReturnCode = 77;

/// Records that the current test case was skipped (test_main.cpp counts them).
void mark_skipped();

} // namespace isodel::testing

#define ISODEL_SKIP(reason)                       \
    do {                                          \
        ::isodel::testing::mark_skipped();        \
        WARN("skipped: " << reason);              \
        return;                                   \
    } while (0)
