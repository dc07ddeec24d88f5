#include "tools/harness/report/result_table.h"

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
  EXPECT_NE(md.find("## Ablation"), std::string::npos);
  EXPECT_NE(md.find("| scenario | orb | Eq. 9 |\n|---|---:|---:|"), std::string::npos);
  EXPECT_NE(md.find("| walk, fast | 0.7322 ± 0.0512 | 98.3 % |"), std::string::npos);
  EXPECT_NE(md.find("| sit | – | – |"), std::string::npos);
}

TEST(ResultTable, CsvHasNumbersOnlyAndQuotesText) {
  EXPECT_EQ(to_csv(example()),
            "scenario,orb,orb std,Eq. 9\n\"walk, fast\",0.73216,0.0512,98.31\nsit,,,\n");
}

TEST(ResultTable, HtmlEscapesText) {
  const std::string html = to_html(example());
  EXPECT_NE(html.find("<p>ATE &lt;m&gt;</p>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">0.7322 ± 0.0512</td>"), std::string::npos);
}

}  // namespace
}  // namespace depot::harness
