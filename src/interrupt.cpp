#include <isodel/errors.h>
#include <isodel/interrupt.h>
#include <isodel/volume.h>

namespace isodel {

void InterruptScope::check(int percent) const
{
    if (intr_ && intr_->wasInterrupted(percent)) throw Cancelled("interrupted");
}

const char* to_string(Inside inside) { return inside == Inside::Above ? "above" : "below"; }

} // namespace isodel
