#pragma once
/// \file interrupt.h
/// Progress reporting, cancellation and tracing, after OpenVDB's interrupter pattern
/// (openvdb/util/NullInterrupter.h): long operations call start(stage), then
/// wasInterrupted(percent) regularly, then end(). Returning true from wasInterrupted makes
/// the operation throw isodel::Cancelled without writing anything. The library prints nothing:
/// its trace lines (one per refinement round and check) go to log(), which ignores them unless
/// the caller overrides it (the CLI's --trace writes them to stderr).

#include <cstdint>

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
    /// Progress of the current stage counted in the units its work is proportional to: \p done
    /// of \p total \p unit ("leaves" before the Delaunay triangulation: OpenVDB leaf nodes and
    /// the leaf-sized blocks at tile faces, never the bounding box's voxels). The default passes
    /// the percentage to wasInterrupted(int).
    /// \return true to request cancellation.
    virtual bool progress(std::uint64_t done, std::uint64_t total, const char* unit)
    {
        (void)unit;
        return wasInterrupted(total > 0 ? int(100 * done / total) : -1);
    }
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
    /// The same, with progress counted in units (Interrupter::progress).
    void check(std::uint64_t done, std::uint64_t total, const char* unit) const;

private:
    Interrupter* intr_;
};

} // namespace isodel
