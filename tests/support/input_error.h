// The message of the InputError a call throws, for tests of bad input.
#pragma once

#include <string>

#include "steadylight/base/error.h"

namespace steadylight::testing {

/// What `call()` throws as an InputError, or "" when it throws nothing.
template <class Call>
std::string input_error_of(Call&& call) {
    try {
        call();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace steadylight::testing
