// The one error type for bad input, in a header of its own so a module can throw it without
// knowing the scene.
#pragma once

#include <stdexcept>

namespace gis {

// Every recoverable problem with input (files, parameters) is reported as this: the message is
// one line that names the problem and where it is. The CLI prints it and exits non-zero.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace gis
