#pragma once
// One table model written three ways: Markdown (for the issue and the
// terminal), CSV (numbers only, a mean and a std column where there is a
// spread) and HTML (for the report).
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace depot::harness {

struct TableColumn {
  TableColumn(std::string name_, int decimals_ = -1, bool with_std_ = false, std::string unit_ = "")
      : name(std::move(name_)), decimals(decimals_), with_std(with_std_), unit(std::move(unit_)) {}
  std::string name;
  int decimals = -1;      // -1: a text column
  bool with_std = false;  // shows "mean ± std"; two CSV columns
  std::string unit;       // appended to numbers in Markdown/HTML ("%")
};

struct TableValue {
  std::string text;  // text columns
  double mean = NAN;
  double std = NAN;
};

struct Table {
  std::string title;
  std::string caption;  // one paragraph under the title
  std::vector<TableColumn> columns;
  std::vector<std::vector<TableValue>> rows;  // one value per column
};

// Numbers: NaN shows as "–" (Markdown/HTML) and as empty (CSV).
std::string to_markdown(const Table& table);
std::string to_csv(const Table& table);
std::string to_html(const Table& table);

}  // namespace depot::harness
