#include <isodel/errors.h>
#include <isodel/interrupt.h>

namespace isodel {

void InterruptScope::check(int percent) const
{
    if (intr_ && intr_->wasInterrupted(percent)) throw Cancelled("interrupted");
}

void InterruptScope::check(std::uint64_t done, std::uint64_t total, const char* unit) const
{
    if (intr_ && intr_->progress(done, total, unit)) throw Cancelled("interrupted");
}

} // namespace isodel
