#include "junit.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace pst {
namespace {

std::string escape(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '&': o += "&amp;"; break;
            case '<': o += "&lt;"; break;
            case '>': o += "&gt;"; break;
            case '"': o += "&quot;"; break;
            case '\'': o += "&apos;"; break;
            default:
                // XML 1.0 allows no control characters but tab, newline and carriage return.
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') o += '?';
                else o += c;
        }
    }
    return o;
}

}  // namespace

std::string junitXml(const std::string& suite, const std::vector<JunitCase>& cases, const JunitProperties& properties) {
    size_t failures = 0, skipped = 0;
    double total = 0;
    for (const auto& c : cases) {
        failures += c.failed;
        skipped += c.skipped && !c.failed;
        total += c.seconds;
    }
    std::ostringstream os;
    char t[32];
    std::snprintf(t, sizeof t, "%.3f", total);
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"" << escape(suite)
       << "\" tests=\"" << cases.size() << "\" failures=\"" << failures << "\" errors=\"0\" skipped=\"" << skipped << "\" time=\"" << t << "\">\n";
    if (!properties.empty()) {
        os << "  <properties>\n";
        for (const auto& [k, v] : properties)
            os << "    <property name=\"" << escape(k) << "\" value=\"" << escape(v) << "\"/>\n";
        os << "  </properties>\n";
    }
    for (const auto& c : cases) {
        std::snprintf(t, sizeof t, "%.3f", c.seconds);
        os << "  <testcase classname=\"" << escape(c.classname) << "\" name=\"" << escape(c.name) << "\" time=\"" << t
           << "\"";
        if (!c.failed && !c.skipped && c.output.empty()) {
            os << "/>\n";
            continue;
        }
        os << ">\n";
        if (c.failed) os << "    <failure message=\"" << escape(c.message) << "\"/>\n";
        else if (c.skipped) os << "    <skipped message=\"" << escape(c.message) << "\"/>\n";
        if (!c.output.empty()) os << "    <system-out>" << escape(c.output) << "</system-out>\n";
        os << "  </testcase>\n";
    }
    os << "</testsuite>\n</testsuites>\n";
    return os.str();
}

void writeJunit(const std::string& path, const std::string& suite, const std::vector<JunitCase>& cases,
                const JunitProperties& properties) {
    std::ofstream f(path);
    f << junitXml(suite, cases, properties);
    if (!f) throw std::runtime_error(path + ": cannot write the JUnit file");
}

}  // namespace pst
