#include <isodel/errors.h>
#include <isodel/interrupt.h>

namespace isodel {

void InterruptScope::check(int percent) const
{
    if (intr_ && intr_->wasInterrupted(percent)) throw Cancelled("interrupted");
}

} // namespace isodel
