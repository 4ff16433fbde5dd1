#pragma once
// Internal: the mesher's self-checks, for tests. The incremental checks (the closed ball
// ViolationFinder, the crease check of refinement/) keep what they found in earlier rounds and
// re-examine only what changed; with self-checks on, each round also computes afresh what it kept
// and throws std::logic_error on a difference. Off by default; a test turns them on for a scope
// with SelfChecksOn. Not part of the public API: the library reads no environment variable for it.
namespace isodel::mesher {

/// Whether the incremental checks verify what they kept (process-wide).
bool incremental_self_checks();
void set_incremental_self_checks(bool on);

/// Turns the self-checks on for its scope (tests).
struct SelfChecksOn {
    SelfChecksOn() { set_incremental_self_checks(true); }
    ~SelfChecksOn() { set_incremental_self_checks(false); }
    SelfChecksOn(const SelfChecksOn&) = delete;
    SelfChecksOn& operator=(const SelfChecksOn&) = delete;
};

} // namespace isodel::mesher
