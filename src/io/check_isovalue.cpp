// The isovalue check shared by every subcommand that takes --iso: a level outside the sample
// range has an empty level set, which is a usage error, not an empty result.
#include <isodel/errors.h>
#include <isodel/volume.h>

#include <cmath>
#include <sstream>

namespace isodel {

void check_isovalue(const Volume& vol, double isovalue)
{
    if (std::isfinite(isovalue) && isovalue >= vol.value_min && isovalue <= vol.value_max) return;
    std::ostringstream msg;
    msg.precision(9);
    msg << vol.path << ": isovalue " << isovalue << " is outside the value range [" << vol.value_min << ", "
        << vol.value_max << "] of the samples";
    throw InvalidInput(msg.str());
}

} // namespace isodel
