#include "tools/harness/report/result_table.h"

#include <fmt/format.h>

#include <cmath>

#include "common/number_text.h"
#include "eval/svg_document.h"

namespace depot::harness {
namespace {

std::string display(const TableColumn& c, const TableValue& v) {
  if (c.decimals < 0) return v.text;
  if (!std::isfinite(v.mean)) return "–";
  std::string s = fixed_number(v.mean, c.decimals) + c.unit;
  if (c.with_std && std::isfinite(v.std)) s += " ± " + fixed_number(v.std, c.decimals) + c.unit;
  return s;
}

// A Markdown cell: '|' would end it and a newline the row.
std::string markdown_cell(const std::string& text) {
  std::string out;
  for (char c : text)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  return fmt::format("{:.9g}", v);
}

}  // namespace

std::string to_markdown(const Table& t) {
  std::string out = "## " + t.title + "\n\n";
  if (!t.caption.empty()) out += t.caption + "\n\n";
  out += "|";
  for (const auto& c : t.columns) out += " " + markdown_cell(c.name) + " |";
  out += "\n|";
  for (const auto& c : t.columns) out += c.decimals < 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& row : t.rows) {
    out += "|";
    for (size_t k = 0; k < t.columns.size(); ++k)
      out += " " + markdown_cell(display(t.columns[k], row[k])) + " |";
    out += "\n";
  }
  return out + "\n";
}

std::string to_csv(const Table& t) {
  std::string out;
  for (size_t k = 0; k < t.columns.size(); ++k) {
    const auto& c = t.columns[k];
    if (k) out += ",";
    out += csv_field(c.name);
    if (c.with_std) out += "," + csv_field(c.name + " std");
  }
  out += "\n";
  for (const auto& row : t.rows) {
    for (size_t k = 0; k < t.columns.size(); ++k) {
      const auto& c = t.columns[k];
      if (k) out += ",";
      out += c.decimals < 0 ? csv_field(row[k].text) : csv_number(row[k].mean);
      if (c.with_std) out += "," + csv_number(row[k].std);
    }
    out += "\n";
  }
  return out;
}

std::string to_html(const Table& t) {
  std::string out = "<h2>" + eval::xml_escape(t.title) + "</h2>\n";
  if (!t.caption.empty()) out += "<p>" + eval::xml_escape(t.caption) + "</p>\n";
  out += "<table>\n<thead><tr>";
  for (const auto& c : t.columns) out += "<th>" + eval::xml_escape(c.name) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    out += "<tr>";
    for (size_t k = 0; k < t.columns.size(); ++k)
      out += std::string(t.columns[k].decimals < 0 ? "<td>" : "<td class=\"num\">") +
             eval::xml_escape(display(t.columns[k], row[k])) + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

}  // namespace depot::harness
