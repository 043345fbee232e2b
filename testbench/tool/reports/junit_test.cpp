// JUnit XML: counts, failures and escaping.
#include "junit.h"

#include <gtest/gtest.h>

namespace pst {
namespace {

TEST(Junit, CountsFailuresAndEscapes) {
    const std::string x = junitXml("suite <1>", {{"regress.full", "marble", 1.5, false, "", ""},
                                                 {"regress.full", "fire & \"ice\"", 0.25, true, "3 mismatches",
                                                  "pixel 7: f rtl 1 golden 2 <bad>\x01"},
                                                 {"regress.full", "bases", 0, false, "no hardware basis", "", true}});
    EXPECT_NE(x.find("<testsuite name=\"suite &lt;1&gt;\" tests=\"3\" failures=\"1\" errors=\"0\" skipped=\"1\" time=\"1.750\">"),
              std::string::npos)
        << x;
    EXPECT_NE(x.find("<testcase classname=\"regress.full\" name=\"marble\" time=\"1.500\"/>"), std::string::npos);
    EXPECT_NE(x.find("name=\"fire &amp; &quot;ice&quot;\""), std::string::npos);
    EXPECT_NE(x.find("<failure message=\"3 mismatches\"/>"), std::string::npos);
    EXPECT_NE(x.find("golden 2 &lt;bad&gt;?</system-out>"), std::string::npos);
    EXPECT_NE(x.find("<skipped message=\"no hardware basis\"/>"), std::string::npos);
    EXPECT_EQ(x.find('\x01'), std::string::npos);
}

}  // namespace
}  // namespace pst
