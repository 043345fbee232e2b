// A user-input error: "file:line: field: what is wrong". Callers exit with status 2.
// inputWhere / inputError write that form for every reader of user files (profiles in
// model/golden/profile.cpp, scenes in testbench/frontend/scene/scene.cpp).
#pragma once

#include <charconv>
#include <stdexcept>
#include <string>

namespace pst {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// "FILE:LINE" (":LINE" left out when line <= 0: not known).
inline std::string inputWhere(const std::string& file, long line) {
    return line > 0 ? file + ":" + std::to_string(line) : file;
}
// "FILE:LINE: FIELD", a message's prefix.
inline std::string inputWhere(const std::string& file, long line, const std::string& field) {
    return inputWhere(file, line) + ": " + field;
}
// InputError("FILE:LINE: FIELD: WHAT").
inline InputError inputError(const std::string& file, long line, const std::string& field, const std::string& what) {
    return InputError(inputWhere(file, line, field) + ": " + what);
}
// A number as a message prints it: the shortest text that reads back as the same double (1e+308,
// 0.1, 1234567), not std::to_string's six fixed decimals (a 1e308 was printed in 316 digits).
inline std::string shortNumber(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}
// The line of a parsed node (toml++'s toml::node or anything with source().begin.line), 0 for
// none.
template <class Node>
long lineOf(const Node* n) {
    return n ? long(n->source().begin.line) : 0;
}

}  // namespace pst
