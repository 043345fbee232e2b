// JUnit XML (the schema CI servers read: Jenkins, GitLab, GitHub test reporters): one
// <testsuite> of test cases, each passed or failed with a message and its output.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pst {

struct JunitCase {
    std::string classname;   // e.g. "regress.full"
    std::string name;        // e.g. "marble" or "random seed 1"
    double seconds = 0;
    bool failed = false;
    std::string message;     // one line: why it failed
    std::string output;      // details (the scoreboard's report)
    bool skipped = false;    // neither passed nor failed; `message` says why
};

// `properties`: the suite's <properties> (provenance.h junitProperties()), none when empty.
using JunitProperties = std::vector<std::pair<std::string, std::string>>;
std::string junitXml(const std::string& suite, const std::vector<JunitCase>& cases, const JunitProperties& properties = {});
// Writes junitXml to `path`; throws std::runtime_error if the file cannot be written.
void writeJunit(const std::string& path, const std::string& suite, const std::vector<JunitCase>& cases,
                const JunitProperties& properties = {});

}  // namespace pst
