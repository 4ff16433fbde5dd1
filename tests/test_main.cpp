// The test executables' main: Catch2's session, OpenVDB initialised, and the skip rule of
// support/skip.h (exit kSkipReturnCode when every executed test case skipped).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <openvdb/openvdb.h>

#include "support/skip.h"

#include <string>

namespace {

int g_cases = 0;
int g_skipped = 0;
std::string g_current;
std::string g_last_skipped;

struct CaseCounter : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;
    void testCaseStarting(Catch::TestCaseInfo const& info) override
    {
        ++g_cases;
        g_current = info.name;
    }
};

} // namespace

CATCH_REGISTER_LISTENER(CaseCounter)

void isodel::testing::mark_skipped()
{
    if (g_last_skipped == g_current) return; // once per test case
    g_last_skipped = g_current;
    ++g_skipped;
}

int main(int argc, char* argv[])
{
    openvdb::initialize();
    const int failures = Catch::Session().run(argc, argv);
    if (failures == 0 && g_cases > 0 && g_skipped == g_cases) return isodel::testing::kSkipReturnCode;
    return failures;
}
