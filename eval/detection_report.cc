#include "eval/detection_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "common/number_text.h"
#include "common/tum_io.h"
#include "eval/series_plot.h"
#include "eval/svg_document.h"

namespace depot::eval {
namespace {

using nlohmann::json;

struct Table {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

// "0.62 (31/50)", or "-" when there is nothing to count.
std::string cell(const Tally& t) {
  if (t.total == 0) return "-";
  return fixed_number(t.rate(), 2) + " (" + std::to_string(t.found) + "/" +
         std::to_string(t.total) + ")";
}

json tally_json(const Tally& t) {
  return {{"found", t.found}, {"total", t.total}, {"rate", t.rate()}};
}

json buckets_json(const std::vector<Tally>& tallies, const std::vector<std::string>& names) {
  json out = json::array();
  for (size_t i = 0; i < tallies.size(); ++i) {
    json b = tally_json(tallies[i]);
    b["bucket"] = names[i];
    out.push_back(b);
  }
  return out;
}

double mean_iou(const ClassTally& t) {
  return t.all.found > 0 ? t.iou_sum / t.all.found : NAN;
}

// Classes worth a row: truth classes with boxes, and every detected class.
std::vector<std::string> shown_classes(const DetectionScore& s) {
  std::vector<std::string> out;
  for (const std::string& c : s.classes()) {
    const ClassTally& t = s.tally(c);
    if (t.all.total > 0 || t.precision.total > 0) out.push_back(c);
  }
  return out;
}

// Why a class's recall is what it is, where the detector decides it.
std::string note(const DetectionSide& side, const std::string& cls) {
  const DetectionScore& s = *side.score;
  const auto& truth = s.truth_classes();
  if (std::find(truth.begin(), truth.end(), cls) == truth.end()) return "detected class only";
  if (side.labels.empty()) return "";
  for (const std::string& l : side.labels)
    if (s.mapping().class_of(l) == cls) return "";
  return s.mapping().reachable(cls, side.labels) ? "any animal label" : "no detector label";
}

Table class_table(const DetectionSide& side) {
  const DetectionScore& s = *side.score;
  Table t{"Per class (IoU >= " + fixed_number(s.rules().min_iou, 2) +
              "; clearly visible: >= " + fixed_number(s.rules().clear_min_height, 0) +
              " px tall, >= " + fixed_number(s.rules().clear_min_visible, 0) + " visible pixels)",
          {"class", "recall (clear)", "recall (all)", "precision", "mean IoU", "note"},
          {}};
  for (const std::string& c : shown_classes(s)) {
    const ClassTally& k = s.tally(c);
    t.rows.push_back({c, cell(k.clear), cell(k.all), cell(k.precision),
                      fixed_number(mean_iou(k), 2), note(side, c)});
  }
  return t;
}

// Recall per catalogue model (mesh actors and props), where the truth names
// them: which asset a class's recall comes from.
Table model_table(const DetectionScore& s) {
  Table t{"Recall per model (the catalogue asset each object is drawn from)",
          {"class", "model", "recall (clear)", "recall (all)"},
          {}};
  for (const auto& [cls, models] : s.by_model())
    for (const auto& [model, k] : models)
      t.rows.push_back({cls, model, cell(k.clear), cell(k.all)});
  return t;
}

Table bucket_table(const DetectionScore& s, bool by_height) {
  const std::vector<std::string> names =
      by_height ? s.rules().height_bucket_names() : s.rules().fill_bucket_names();
  Table t{by_height ? "Recall by box height (px), all boxes"
                    : "Recall by visible fraction (visible pixels / box area), all boxes",
          {"class"},
          {}};
  t.header.insert(t.header.end(), names.begin(), names.end());
  for (const std::string& c : s.truth_classes()) {
    const ClassTally& k = s.tally(c);
    if (k.all.total == 0) continue;
    std::vector<std::string> row{c};
    for (const Tally& b : by_height ? k.by_height : k.by_fill) row.push_back(cell(b));
    t.rows.push_back(row);
  }
  return t;
}

Table confusion_table(const DetectionScore& s, bool clear_only) {
  const auto& conf = s.confusion(clear_only);
  std::vector<std::string> columns;
  for (const std::string& c : s.classes())
    for (const auto& [truth, row] : conf)
      if (row.count(c) && std::find(columns.begin(), columns.end(), c) == columns.end())
        columns.push_back(c);
  for (const auto& [truth, row] : conf)
    for (const auto& [called, n] : row)
      if (called != DetectionScore::kMissed &&
          std::find(columns.begin(), columns.end(), called) == columns.end())
        columns.push_back(called);
  columns.push_back(DetectionScore::kMissed);
  Table t{std::string("Confusion (") + (clear_only ? "clearly visible" : "all") +
              " boxes): truth class x detected class, matched at IoU >= " +
              fixed_number(s.rules().min_iou, 2),
          {"truth \\ detected"},
          {}};
  t.header.insert(t.header.end(), columns.begin(), columns.end());
  for (const std::string& c : s.truth_classes()) {
    const auto it = conf.find(c);
    if (it == conf.end()) continue;
    std::vector<std::string> row{c};
    for (const std::string& col : columns) {
      const auto n = it->second.find(col);
      row.push_back(n == it->second.end() ? "." : std::to_string(n->second));
    }
    t.rows.push_back(row);
  }
  return t;
}

std::string summary_line(const DetectionSide& side) {
  const DetectionScore& s = *side.score;
  return fmt::format(
      "{} frames; {} false positives ({} per frame); {} detections of unscored labels; detector "
      "{}, median {:.1f} ms per frame",
      s.frames(), s.false_positives(), fixed_number(s.false_positives_per_frame(), 3),
      s.other_detections(), side.detector, side.median_ms);
}

std::string text(const Table& t) {
  std::vector<size_t> width(t.header.size(), 0);
  auto widen = [&](const std::vector<std::string>& row) {
    for (size_t i = 0; i < row.size() && i < width.size(); ++i)
      width[i] = std::max(width[i], row[i].size());
  };
  widen(t.header);
  for (const auto& r : t.rows) widen(r);
  std::string out = t.title + "\n";
  auto line = [&](const std::vector<std::string>& row) {
    std::string l = " ";
    for (size_t i = 0; i < row.size(); ++i) {
      const std::string pad(width[i] - row[i].size(), ' ');
      l += " " + (i == 0 ? row[i] + pad : pad + row[i]);
    }
    while (!l.empty() && l.back() == ' ') l.pop_back();
    out += l + "\n";
  };
  line(t.header);
  for (const auto& r : t.rows) line(r);
  if (t.rows.empty()) out += "  (none)\n";
  return out;
}

std::string markdown(const Table& t) {
  std::string out = "**" + t.title + "**\n\n|";
  for (const std::string& h : t.header) out += " " + h + " |";
  out += "\n|";
  for (size_t i = 0; i < t.header.size(); ++i) out += i == 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& r : t.rows) {
    out += "|";
    for (const std::string& c : r) out += " " + c + " |";
    out += "\n";
  }
  return out + "\n";
}

std::string html(const Table& t) {
  std::string out = "<h4>" + xml_escape(t.title) + "</h4>\n<table>\n<tr>";
  for (const std::string& h : t.header) out += "<th>" + xml_escape(h) + "</th>";
  out += "</tr>\n";
  for (const auto& r : t.rows) {
    out += "<tr>";
    for (size_t i = 0; i < r.size(); ++i)
      out += (i == 0 ? "<th>" : "<td>") + xml_escape(r[i]) + (i == 0 ? "</th>" : "</td>");
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

std::vector<Table> side_tables(const DetectionSide& side) {
  std::vector<Table> tables{class_table(side), bucket_table(*side.score, true),
                            bucket_table(*side.score, false), confusion_table(*side.score, true)};
  if (!side.score->by_model().empty()) tables.insert(tables.begin() + 1, model_table(*side.score));
  return tables;
}

// Clearly visible recall and precision of every side, class by class.
Table gap_table(const std::vector<DetectionSide>& sides) {
  Table t{"Side by side: recall of clearly visible boxes, and precision", {"class"}, {}};
  std::vector<std::string> classes;
  for (const DetectionSide& side : sides) {
    t.header.push_back(side.name + " recall (clear)");
    t.header.push_back(side.name + " precision");
    for (const std::string& c : side.score->truth_classes())
      if (side.score->tally(c).all.total > 0 &&
          std::find(classes.begin(), classes.end(), c) == classes.end())
        classes.push_back(c);
  }
  for (const std::string& c : classes) {
    std::vector<std::string> row{c};
    for (const DetectionSide& side : sides) {
      row.push_back(cell(side.score->tally(c).clear));
      row.push_back(cell(side.score->tally(c).precision));
    }
    t.rows.push_back(row);
  }
  return t;
}

std::string recall_plot(const DetectionSide& side) {
  const DetectionScore& s = *side.score;
  SeriesPlot plot;
  plot.title = "Recall by box height: " + side.name;
  plot.x_label = "box height (px)";
  plot.y_label = "recall (IoU >= " + fixed_number(s.rules().min_iou, 2) + ")";
  plot.x_levels = s.rules().height_bucket_names();
  plot.y_lo = 0.0;
  plot.y_hi = 1.0;
  for (const std::string& c : s.truth_classes()) {
    const ClassTally& k = s.tally(c);
    if (k.all.total == 0) continue;
    PlotSeries series;
    series.name = c;
    series.colour = series_colour(plot.series.size());
    for (const Tally& b : k.by_height) {
      series.mean.push_back(b.rate());
      series.std.push_back(NAN);
    }
    plot.series.push_back(series);
  }
  return render_series_plot_svg(plot);
}

}  // namespace

json detection_side_json(const DetectionSide& side) {
  const DetectionScore& s = *side.score;
  const DetectionRules& r = s.rules();
  json classes = json::object();
  for (const std::string& c : s.classes()) {
    const ClassTally& k = s.tally(c);
    classes[c] = {{"recall_all", tally_json(k.all)},
                  {"recall_clear", tally_json(k.clear)},
                  {"precision", tally_json(k.precision)},
                  {"mean_iou", mean_iou(k)},
                  {"by_height", buckets_json(k.by_height, r.height_bucket_names())},
                  {"by_visible_fraction", buckets_json(k.by_fill, r.fill_bucket_names())},
                  {"note", note(side, c)}};
  }
  json confusion = json::object(), confusion_clear = json::object();
  for (const auto& [truth, row] : s.confusion(false)) confusion[truth] = row;
  for (const auto& [truth, row] : s.confusion(true)) confusion_clear[truth] = row;
  return {{"name", side.name},
          {"detector", side.detector},
          {"class_mapping", s.mapping().path()},
          {"rules",
           {{"min_iou", r.min_iou},
            {"clear_min_height_px", r.clear_min_height},
            {"clear_min_visible_pixels", r.clear_min_visible},
            {"height_edges_px", r.height_edges},
            {"visible_fraction_edges", r.fill_edges}}},
          {"frames", s.frames()},
          {"median_ms", side.median_ms},
          {"false_positives", s.false_positives()},
          {"false_positives_per_frame", s.false_positives_per_frame()},
          {"unscored_detections", s.other_detections()},
          {"classes", classes},
          {"confusion", confusion},
          {"confusion_clear", confusion_clear}};
}

std::string detection_text(const DetectionSide& side) {
  std::string out = side.name + "\n";
  for (const Table& t : side_tables(side)) out += text(t);
  return out + summary_line(side) + "\n";
}

std::string detection_gap_text(const std::vector<DetectionSide>& sides) {
  return text(gap_table(sides));
}

void write_detection_report(const std::string& dir, const std::string& title,
                            const std::vector<DetectionSide>& sides) {
  namespace fs = std::filesystem;
  std::string md = "# " + title + "\n\n", page;
  page = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + xml_escape(title) +
         "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:1100px}"
         "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;"
         "padding:3px 8px;text-align:right}th:first-child{text-align:left}"
         "tr:first-child th{background:#f0f0f0}</style></head><body>\n<h1>" +
         xml_escape(title) + "</h1>\n";
  if (sides.size() > 1) {
    const Table gap = gap_table(sides);
    md += markdown(gap);
    page += html(gap);
  }
  for (size_t i = 0; i < sides.size(); ++i) {
    const DetectionSide& side = sides[i];
    const std::string svg_name = "recall_vs_height_" + std::to_string(i + 1) + ".svg";
    const std::string svg = recall_plot(side);
    write_text_file_atomic((fs::path(dir) / svg_name).string(), svg);
    md += "## " + side.name + "\n\n" + summary_line(side) + "\n\n![recall vs box height](" +
          svg_name + ")\n\n";
    page += "<h2>" + xml_escape(side.name) + "</h2>\n<p>" + xml_escape(summary_line(side)) +
            "</p>\n" + svg + "\n";
    for (const Table& t : side_tables(side)) {
      md += markdown(t);
      page += html(t);
    }
  }
  page += "</body></html>\n";
  write_text_file_atomic((fs::path(dir) / "report.md").string(), md);
  write_text_file_atomic((fs::path(dir) / "report.html").string(), page);
}

}  // namespace depot::eval
