#include "self_checks.h"

#include <atomic>

namespace isodel::mesher {
namespace {
std::atomic<bool> g_incremental_self_checks{false};
}

bool incremental_self_checks() { return g_incremental_self_checks.load(std::memory_order_relaxed); }
void set_incremental_self_checks(bool on) { g_incremental_self_checks.store(on, std::memory_order_relaxed); }

} // namespace isodel::mesher
