#pragma once
/// \file interrupt.h
/// Progress reporting, cancellation and tracing, after OpenVDB's interrupter pattern
/// (openvdb/util/NullInterrupter.h): long operations call start(stage), then
/// wasInterrupted(percent) regularly, then end(). Returning true from wasInterrupted makes
/// the operation throw isodel::Cancelled without writing anything. The library prints nothing:
/// its trace lines (one per refinement round and check) go to log(), which ignores them unless
/// the caller overrides it (the CLI's --trace writes them to stderr).

namespace isodel {

class Interrupter {
public:
    virtual ~Interrupter() = default;
    /// A new stage begins; \p name is a short lower-case stage name ("read", "delaunay", ...).
    virtual void start(const char* name) { (void)name; }
    /// The current stage ended.
    virtual void end() {}
    /// Progress of the current stage in percent (0..100), or -1 when unknown.
    /// \return true to request cancellation.
    virtual bool wasInterrupted(int percent = -1) { (void)percent; return false; }
    /// A trace line (no trailing newline), from the thread that called the library or from a
    /// worker thread: an override that writes somewhere shared must serialise its writes.
    virtual void log(const char* message) { (void)message; }
};

/// Never interrupts, reports nothing.
class NullInterrupter final : public Interrupter {};

/// RAII helper used inside the library: start() on construction, end() on destruction,
/// check(percent) throws Cancelled when the interrupter asks to stop.
class InterruptScope {
public:
    InterruptScope(Interrupter* intr, const char* name) : intr_(intr) { if (intr_) intr_->start(name); }
    ~InterruptScope() { if (intr_) intr_->end(); }
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;
    /// Throws isodel::Cancelled if the interrupter requests it.
    void check(int percent = -1) const;

private:
    Interrupter* intr_;
};

} // namespace isodel
