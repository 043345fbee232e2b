#include "fragments.h"

#include <sstream>

#include <gtest/gtest.h>

#include "scene.h"

namespace pst {
namespace {

TEST(Fragments, RoundTripIsExact) {
    std::vector<FragmentRecord> in = {{{0.1, -2.5e-7, 1e6}, {1.0 / 3.0, 0, -0.0}, {1e-300, 7, 8}},
                                      {{-1, -2, -3}, {4, 5, 6}, {7, 8, 9}}};
    std::stringstream ss;
    writeFragments(ss, in);
    auto out = readFragments(ss, "rt");
    ASSERT_EQ(out.size(), in.size());
    for (size_t i = 0; i < in.size(); ++i) {
        EXPECT_EQ(out[i].s, in[i].s);
        EXPECT_EQ(out[i].dsdx, in[i].dsdx);
        EXPECT_EQ(out[i].dsdy, in[i].dsdy);
    }
}

void expectError(const std::string& text, const std::string& part) {
    std::istringstream in(text);
    try {
        readFragments(in, "f.txt");
        FAIL() << "no error for: " << text;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

TEST(Fragments, BadInput) {
    expectError("# c\n1 2 3 4 5 6 7 8 9\n1 2 3 4 5 6 7 8\n", "f.txt:3: line: expected 9 numbers");
    expectError("1 2 3 4 5 6 7 8 9 10\n", "f.txt:1: line: more than 9");
    expectError("1 2 x 4 5 6 7 8 9\n", "f.txt:1: r: not a number: 'x'");
    expectError("1 2 3 nan 5 6 7 8 9\n", "f.txt:1: ds/dx: NaN");
    expectError("1 2 3 4 5 6 7 8 inf\n", "f.txt:1: dr/dy: NaN, infinite");
    expectError("1 2 3 4 5 6 7 8 1e999\n", "f.txt:1: dr/dy");
    expectError("1 2 3 4 5 6 7 8 9x\n", "f.txt:1: dr/dy: not a number");
}

TEST(Fragments, CommentsAndBlankLines) {
    std::istringstream in("\n# header\n  1 2 3 4 5 6 7 8 9  # trailing\n\n");
    EXPECT_EQ(readFragments(in, "f").size(), 1u);
}

}  // namespace
}  // namespace pst
