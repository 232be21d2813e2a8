// zenith/base: the error family, range messages, atomic files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "zenith/base/atomic_file.h"
#include "zenith/base/error.h"
#include "zenith/base/gauss_legendre.h"
#include "zenith/base/text_lines.h"
#include "zenith/base/units.h"

namespace zenith {
namespace {

using ::testing::HasSubstr;

TEST(Range, ContainsRespectsOpenEndsAndRejectsNan) {
    EXPECT_TRUE(Range::Closed(0, 1).Contains(0.0));
    EXPECT_TRUE(Range::Closed(0, 1).Contains(1.0));
    EXPECT_FALSE(Range::Open(0, 1).Contains(0.0));
    EXPECT_FALSE(Range::Open(0, 1).Contains(1.0));
    EXPECT_TRUE(Range::LeftOpen(0, 1).Contains(1.0));
    EXPECT_FALSE(Range::RightOpen(0, 1).Contains(1.0));
    EXPECT_FALSE(Range::Closed(0, 1).Contains(std::numeric_limits<double>::quiet_NaN()));
    EXPECT_FALSE(Range::Closed(0, 1e300).Contains(std::numeric_limits<double>::infinity()));
}

TEST(Require, MessageNamesFieldValueUnitAndRange) {
    EXPECT_EQ(Require("fov", 60.0, "deg", Range::Open(0, 180)), 60.0);
    try {
        Require("fov", 200.0, "deg", Range::Open(0, 180));
        FAIL() << "no throw";
    } catch (const ArgumentError& e) {
        EXPECT_STREQ(e.what(), "fov = 200 deg is out of range (expected (0, 180) deg)");
    }
    try {
        Require("coverage", std::numeric_limits<double>::quiet_NaN(), "", Range::Closed(0, 1));
        FAIL() << "no throw";
    } catch (const Error& e) {  // every zenith error is a zenith::Error
        EXPECT_STREQ(e.what(), "coverage = nan is out of range (expected [0, 1])");
    }
}

TEST(Require, ThrowsTheRequestedType) {
    EXPECT_THROW(Require<InputError>("x", -1.0, "m", Range::Closed(0, 1)), InputError);
}

TEST(AtLocation, FileAndLine) {
    EXPECT_EQ(AtLocation("a/b.csv", 12, "bad time"), "a/b.csv:12: bad time");
    EXPECT_EQ(AtLocation("a/b.csv", std::nullopt, "empty"), "a/b.csv: empty");
}

TEST(Units, Conversions) {
    EXPECT_DOUBLE_EQ(Radians(180.0), kPi);
    EXPECT_DOUBLE_EQ(Degrees(kPi / 2.0), 90.0);
    EXPECT_DOUBLE_EQ(3.0 * kMetresPerFoot, 0.9144);
}

class AtomicFileTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ =
            std::filesystem::temp_directory_path() /
            ("zenith_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(AtomicFileTest, ReplacesTheFileWhole) {
    const auto path = dir_ / "a.txt";
    WriteFileAtomically(path, "first");
    WriteFileAtomically(path, "second, longer");
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "second, longer");
    EXPECT_FALSE(std::filesystem::exists(dir_ / "a.txt.partial"));
}

TEST_F(AtomicFileTest, FailureNamesThePathAndLeavesNothing) {
    const auto path = dir_ / "missing" / "a.txt";
    try {
        WriteFileAtomically(path, "x");
        FAIL() << "no throw";
    } catch (const FileError& e) {
        EXPECT_THAT(e.what(), HasSubstr(path.string()));
        EXPECT_THAT(e.what(), HasSubstr("No such file"));
    }
    EXPECT_FALSE(std::filesystem::exists(path.string() + ".partial"));
}

}  // namespace
}  // namespace zenith

namespace zenith {
namespace {

TEST(CsvLine, QuotesCommasAndUnclosedFields) {
    std::vector<std::string> fields;
    EXPECT_TRUE(SplitCsvLine("a,\"b,c\",\"say \"\"hi\"\"\",", fields));
    EXPECT_EQ(fields, (std::vector<std::string>{"a", "b,c", "say \"hi\"", ""}));
    EXPECT_TRUE(SplitCsvLine("", fields));
    EXPECT_EQ(fields, (std::vector<std::string>{""}));
    EXPECT_FALSE(SplitCsvLine("a,\"open", fields));
}

// The n-point rule integrates x^k over [-1, 1] exactly (2 / (k + 1) for even k, 0 for odd) up
// to k = 2n - 1, and not beyond (where the miss is still large enough to see); the two-point
// rule's nodes are -+1/sqrt(3).
TEST(GaussLegendre, IsExactForPolynomialsUpToDegreeTwoNMinusOne) {
    for (const int n : {1, 2, 5, 16, 48}) {
        const GaussLegendreRule rule = GaussLegendre(n);
        ASSERT_EQ(rule.nodes.size(), static_cast<std::size_t>(n));
        for (int k = 0; k <= 2 * n; ++k) {
            double sum = 0.0;
            for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
                sum += rule.weights[i] * std::pow(rule.nodes[i], k);
            }
            const double exact = k % 2 == 0 ? 2.0 / (k + 1) : 0.0;
            if (k < 2 * n) {
                EXPECT_NEAR(sum, exact, 1e-13) << "n " << n << " k " << k;
            } else if (n <= 5) {  // beyond, its error falls below 1e-9 by n = 16
                EXPECT_GT(std::abs(sum - exact), 1e-6) << "n " << n << " k " << k;
            }
        }
        for (std::size_t i = 1; i < rule.nodes.size(); ++i) {
            EXPECT_LT(rule.nodes[i - 1], rule.nodes[i]);
        }
    }
    const GaussLegendreRule two = GaussLegendre(2);
    EXPECT_NEAR(two.nodes[1], 1.0 / std::sqrt(3.0), 1e-15);
    EXPECT_THROW(GaussLegendre(0), ArgumentError);
}

// On [a, b] the rule integrates x^k to (b^(k+1) - a^(k+1)) / (k + 1) up to k = 2n - 1, its
// nodes inside the interval.
TEST(GaussLegendre, MapsOntoAnyInterval) {
    for (const auto& [a, b] : {std::pair{0.0, 1.0}, std::pair{-0.5, 3.0}}) {
        const GaussLegendreRule rule = GaussLegendre(5, a, b);
        EXPECT_GT(rule.nodes.front(), a);
        EXPECT_LT(rule.nodes.back(), b);
        for (int k = 0; k < 10; ++k) {
            double sum = 0.0;
            for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
                sum += rule.weights[i] * std::pow(rule.nodes[i], k);
            }
            const double exact = (std::pow(b, k + 1) - std::pow(a, k + 1)) / (k + 1);
            EXPECT_NEAR(sum, exact, 1e-12 * std::max(1.0, std::abs(exact))) << a << " " << k;
        }
    }
}

}  // namespace
}  // namespace zenith
