#include "tools/harness/report/sweep_report.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/tum_io.h"
#include "eval/svg_document.h"
#include "tools/harness/report/breaking_points.h"
#include "tools/harness/report/result_table.h"
#include "tools/harness/report/sweep_figures.h"
#include "tools/harness/report/sweep_summary.h"
#include "tools/harness/report/sweep_tables.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

const char* kStyle = R"(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; margin: 24px 32px; color: #222; max-width: 1400px; }
h1 { font-size: 24px; margin-bottom: 4px; }
h2 { font-size: 18px; margin-top: 32px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
p, li { font-size: 14px; line-height: 1.45; }
table { border-collapse: collapse; font-size: 13px; margin: 8px 0 16px 0; }
th, td { border: 1px solid #ccc; padding: 4px 8px; }
th { background: #f0f3f7; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tbody tr:nth-child(even) { background: #fafafa; }
.figures { display: flex; flex-wrap: wrap; gap: 16px; }
.figure { border: 1px solid #e2e2e2; padding: 6px; background: #fff; flex: 1 1 560px; max-width: 700px; }
.figure.wide { flex-basis: 100%; max-width: 1300px; }
.figure svg { display: block; max-width: 100%; height: auto; }
.world { border: 1px solid #e2e2e2; padding: 6px; background: #fff; flex: 0 1 480px; }
.world img { display: block; max-width: 100%; height: auto; }
.world p { margin: 4px 0 0 0; font-size: 12px; }
.status { background: #f7f7e8; border: 1px solid #e0e0b0; padding: 8px 12px; display: inline-block; }
code { background: #f3f3f3; padding: 1px 4px; }
)";

// An SVG file's markup without its XML declaration, to embed in HTML.
std::string inline_svg(const std::string& svg) {
  const size_t start = svg.find("<svg");
  return start == std::string::npos ? svg : svg.substr(start);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string spec_html(const SweepPlan& plan, const SweepSummary& summary) {
  const SweepSpec& spec = plan.spec;
  std::string out = "<ul>\n<li>scenarios: ";
  for (size_t i = 0; i < spec.scenarios.size(); ++i)
    out += (i ? ", " : "") + eval::xml_escape(spec.scenarios[i].name);
  out += "</li>\n";
  for (const auto& p : spec.vary) {
    out += "<li>varied: <code>" + eval::xml_escape(p.name) + "</code> = ";
    for (size_t i = 0; i < p.values.size(); ++i)
      out += (i ? ", " : "") + eval::xml_escape(p.values[i]);
    out += "</li>\n";
  }
  for (const auto& p : spec.fixed)
    out += "<li>fixed: <code>" + eval::xml_escape(p.name) + "=" + eval::xml_escape(p.values[0]) +
           "</code></li>\n";
  out += "<li>modes: ";
  for (size_t i = 0; i < spec.modes.size(); ++i)
    out += (i ? ", " : "") + eval::xml_escape(spec.modes[i]);
  out += "</li>\n<li>" + std::to_string(spec.seeds) + " seed(s), " + std::to_string(spec.frames) +
         " frames at " + std::to_string(spec.width) +
         " px, simulated detector at its default "
         "error level unless a detector parameter is varied, local mapping " +
         (spec.sync_mapping ? "in the tracking thread (reproducible)" : "threaded") +
         "</li>\n</ul>\n";
  size_t without_trajectory = 0;
  for (const auto& r : summary.runs) without_trajectory += !r.ok;
  // The words of `depot sweep status` (sweep_job_state.h).
  std::string notes;
  if (without_trajectory)
    notes += ", " + std::to_string(without_trajectory) + " without a trajectory";
  if (summary.failed_jobs) notes += ", " + std::to_string(summary.failed_jobs) + " failed";
  if (!summary.corrupt.empty())
    notes += ", " + std::to_string(summary.corrupt.size()) + " with a corrupt record (left out)";
  out += "<p class=\"status\">" + std::to_string(summary.runs.size()) + " of " +
         std::to_string(summary.expected_runs) + " runs finished" + notes +
         (summary.runs.size() < summary.expected_runs
              ? ". The sweep is incomplete: resume it with <code>depot sweep resume</code>."
              : ".") +
         "</p>\n";
  return out;
}

}  // namespace

ReportFiles write_sweep_report(const SweepPlan& plan, const SweepLayout& layout,
                               const std::vector<std::string>& figure_runs) {
  for (const auto& id : figure_runs) find_job(plan, id, "--figures");  // before writing anything
  const SweepSummary summary = summarize_sweep(plan, layout);
  const std::string dir = layout.report_dir();
  fs::create_directories(dir);
  ReportFiles files;
  files.runs_found = summary.runs.size();
  files.runs_expected = summary.expected_runs;
  files.corrupt = summary.corrupt;

  const struct {
    const char* csv;
    Table table;
  } tables[] = {{"table2_ablation.csv", ablation_table(plan, summary)},
                {"table3_ate_vs_orb.csv", ate_against_orb_table(plan, summary)},
                {"table4_rpe_vs_orb.csv", rpe_against_orb_table(plan, summary)},
                {"rejection.csv", rejection_table(plan, summary)},
                {"breaking_points.csv", breaking_point_table(plan, summary)},
                {"frames.csv", frames_table(plan, summary)},
                {"runs.csv", runs_table(plan, summary)}};
  std::string markdown = "# Sweep report: " + layout.root + "\n\n";
  std::string tables_html;
  for (const auto& t : tables) {
    if (t.table.rows.empty() && std::string(t.csv) != "runs.csv") continue;
    write_text_file_atomic((fs::path(dir) / t.csv).string(), to_csv(t.table));
    if (std::string(t.csv) == "runs.csv") continue;  // long: CSV and HTML only
    markdown += to_markdown(t.table);
    tables_html += to_html(t.table);
  }
  files.ablation_markdown = to_markdown(tables[0].table);
  files.markdown = (fs::path(dir) / "tables.md").string();
  write_text_file_atomic(files.markdown, markdown);

  std::string figures_html;
  for (const Figure& f : sweep_figures(plan, summary)) {
    write_text_file_atomic((fs::path(dir) / f.file).string(), f.svg);
    figures_html += "<div class=\"figure\">" + inline_svg(f.svg) + "</div>\n";
  }
  std::string trajectories_html;
  for (const auto& id : figure_runs.empty() ? default_figure_runs(plan) : figure_runs) {
    const std::string svg = (fs::path(layout.run_dir(id)) / "ate.svg").string();
    if (!fs::is_regular_file(svg)) continue;
    trajectories_html += "<div class=\"figure wide\"><p>" + eval::xml_escape(id) + "</p>" +
                         inline_svg(read_file(svg)) + "</div>\n";
  }

  // The worlds rendered: each dataset's contact sheet, scenario and seed
  // (a generated hall differs by seed), linked from the sweep's data folder.
  std::string worlds_html;
  for (const SweepJob& job : plan.jobs) {
    if (job.kind != JobKind::kRender || !fs::is_regular_file(layout.dataset_preview(job.id)))
      continue;
    const std::string link = fs::relative(layout.dataset_preview(job.id), dir).generic_string();
    worlds_html += "<div class=\"world\"><img src=\"" + eval::xml_escape(link) + "\" alt=\"\"><p>" +
                   eval::xml_escape(job.id) + "</p></div>\n";
  }

  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>depot sweep report</title>\n<style>" +
      std::string(kStyle) + "</style>\n</head>\n<body>\n";
  html += "<h1>depot sweep report</h1>\n<p>" + eval::xml_escape(layout.root) + "</p>\n";
  html += spec_html(plan, summary);
  if (!figures_html.empty())
    html += "<h2>Plots</h2>\n<div class=\"figures\">\n" + figures_html + "</div>\n";
  html += tables_html;
  if (!trajectories_html.empty())
    html +=
        "<h2>Trajectories (ground truth vs estimate, coloured by ATE; paper Figs. 6-7)</h2>\n"
        "<div class=\"figures\">\n" +
        trajectories_html + "</div>\n";
  if (!worlds_html.empty())
    html +=
        "<h2>Worlds rendered (RGB | depth | labels of the first frame)</h2>\n"
        "<div class=\"figures\">\n" +
        worlds_html + "</div>\n";
  // Every run, at the end (long: CSV and HTML only, not in tables.md).
  for (const auto& t : tables)
    if (std::string(t.csv) == "runs.csv") html += to_html(t.table);
  html += "</body>\n</html>\n";
  files.html = (fs::path(dir) / "report.html").string();
  write_text_file_atomic(files.html, html);
  return files;
}

}  // namespace depot::harness
