// A user-input error: "file:line: field: what is wrong". Callers exit with status 2.
#pragma once

#include <stdexcept>

namespace pst {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace pst
