#include "tools/harness/report/result_table.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace depot::harness {
namespace {

Table example() {
  Table t;
  t.title = "Ablation";
  t.caption = "ATE <m>";
  t.columns = {{"scenario"}, {"orb", 4, true}, {"Eq. 9", 1, false, " %"}};
  t.rows = {{{"walk, fast", NAN, NAN}, {"", 0.73216, 0.0512}, {"", 98.31, NAN}},
            {{"sit", NAN, NAN}, {"", NAN, NAN}, {"", NAN, NAN}}};
  return t;
}

TEST(ResultTable, MarkdownShowsMeanAndStdAndDashesForMissing) {
  const std::string md = to_markdown(example());
  EXPECT_THAT(md, ::testing::HasSubstr("## Ablation"));
  EXPECT_THAT(md, ::testing::HasSubstr("| scenario | orb | Eq. 9 |\n|---|---:|---:|"));
  EXPECT_NE(md.find("| walk, fast | 0.7322 ± 0.0512 | 98.3 % |"), std::string::npos);
  EXPECT_THAT(md, ::testing::HasSubstr("| sit | – | – |"));
}

TEST(ResultTable, CsvHasNumbersOnlyAndQuotesText) {
  EXPECT_EQ(to_csv(example()),
            "scenario,orb,orb std,Eq. 9\n\"walk, fast\",0.73216,0.0512,98.31\nsit,,,\n");
}

TEST(ResultTable, HtmlEscapesText) {
  const std::string html = to_html(example());
  EXPECT_THAT(html, ::testing::HasSubstr("<p>ATE &lt;m&gt;</p>"));
  EXPECT_THAT(html, ::testing::HasSubstr("<td class=\"num\">0.7322 ± 0.0512</td>"));
}

}  // namespace
}  // namespace depot::harness
