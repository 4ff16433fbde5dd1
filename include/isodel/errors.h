#pragma once
/// \file errors.h
/// The exceptions isodel throws. Every message is one line that names the file or the
/// option concerned and the problem; the CLI prints it as is and maps the type to an exit code
/// (InvalidInput, IoError -> 2; GuaranteeViolated -> 1; Cancelled -> 130).
#include <stdexcept>
#include <string>

namespace isodel {

/// Base of every isodel exception.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The input (a file, a grid, an option) is unusable: wrong format, inconsistent header,
/// non-finite samples, isovalue outside the value range, ...
struct InvalidInput : Error {
    using Error::Error;
};

/// A file could not be opened, read or written.
struct IoError : Error {
    using Error::Error;
};

/// A stated bound of the algorithm was hit (iteration cap, point cap, voxel bound) so a
/// guarantee cannot be certified. The message says which bound stopped the run.
struct GuaranteeViolated : Error {
    using Error::Error;
};

/// The caller's Interrupter asked to stop.
struct Cancelled : Error {
    using Error::Error;
};

} // namespace isodel
