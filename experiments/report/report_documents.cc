#include "experiments/report/report_documents.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cmt::report {
namespace {

const char* const kTitle = "cmt results report";

// Inside a Markdown table cell a "|" ends the cell and a newline ends the row.
std::string md_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out;
}

// Code spans: a backtick inside needs a longer fence; commands have none, JSON neither, so double is enough.
// (Built with += only: GCC 12 reports a false -Wrestrict on "literal" + std::string, its bug 105329.)
std::string md_code(const std::string& s) {
  const std::string fence = s.find('`') == std::string::npos ? "`" : "`` ";
  std::string out = fence;
  out += md_escape(s);
  out += fence.size() == 1 ? "`" : " ``";
  return out;
}

std::string md_span(const Span& s) {
  std::string out;
  if (!s.image.empty()) {
    out += "![";
    out += md_escape(s.text);
    out += "](";
    out += s.image;
    out += ')';
    if (s.href.empty()) return out;
    return "[" + out + "](" + s.href + ")";
  }
  if (!s.href.empty()) {
    out += '[';
    out += md_escape(s.text);
    out += "](";
    out += s.href;
    out += ')';
  } else if (s.code)
    out += md_code(s.text);
  else
    out += md_escape(s.text);
  return out;
}

std::string md_cell(const Cell& cell) {
  std::string out;
  for (const Span& s : cell) {
    if (!out.empty()) out += ' ';
    out += md_span(s);
  }
  return out;
}

// Thumbnails are shown at this width; the PNG is the full figure, one click away.
constexpr int kThumbnailWidth = 120;

std::string html_span(const Span& s) {
  std::string out;
  if (!s.image.empty()) {
    out = "<img class=\"thumb\" src=\"" + html_escape(s.image) + "\" alt=\"" + html_escape(s.text) +
          "\" width=\"" + std::to_string(kThumbnailWidth) + "\">";
    return s.href.empty() ? out : "<a href=\"" + html_escape(s.href) + "\">" + out + "</a>";
  }
  if (!s.href.empty()) return "<a href=\"" + html_escape(s.href) + "\">" + html_escape(s.text) + "</a>";
  if (s.code) return "<code>" + html_escape(s.text) + "</code>";
  return html_escape(s.text);
}

std::string html_cell(const Cell& cell) {
  std::string out;
  for (const Span& s : cell) {
    if (!out.empty()) out += ' ';
    out += html_span(s);
  }
  return out;
}

// ---- Markdown ----

void md_summary(std::ostream& md, const ReportContent& c) {
  md << "## Summary\n\n";
  for (const SummaryLine& line : c.summary)
    md << "- **" << line.label << ":** " << md_escape(line.text) << "\n";
  md << "\n";
}

void md_table(std::ostream& md, const Table& t) {
  md << "|";
  for (const std::string& h : t.headers) md << " " << md_escape(h) << " |";
  md << "\n|";
  for (std::size_t i = 0; i < t.headers.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& row : t.rows) {
    md << "|";
    for (const Cell& cell : row) md << " " << md_cell(cell) << " |";
    md << "\n";
  }
  md << "\n";
}

// The adversarial search's table (report_table.h falsify_table), when some configuration has one.
constexpr const char* kFalsifyTitle = "Adversarial rollouts";
constexpr const char* kFalsifyIntro =
    "Per unit with an adversarial search (cmt falsify against the unit's prediction, its N rollouts as the "
    "random baseline; docs/falsify.md): search rollouts of every phase, the motion ends outside the "
    "prediction the search found, the largest signed distance from each motion's predicted set the "
    "falsification reached (> 0: outside), coverage before (the N rollouts) and after (every rollout), "
    "the predicted pieces no rollout ended in, and the gap search's targets (coverage lattice points far "
    "from every end) reached and not.";

void md_falsify(std::ostream& md, const Table& t) {
  if (t.rows.empty()) return;
  md << "## " << kFalsifyTitle << "\n\n" << kFalsifyIntro << "\n\n";
  md_table(md, t);
}

constexpr const char* kTeachingTitle = "Teaching sessions";
constexpr const char* kTeachingIntro =
    "Per scripted teaching session (cmt teach, Buckley ch. 5; docs/teaching.md): whether the start was "
    "solved, "
    "the taught strategy, per step the chain tried and the measure of the start it solved and left (with the "
    "verifier's reason), and the pre-image check: MuJoCo rollouts from every solved start cell, each of "
    "which must reach the goal.";

void md_teaching(std::ostream& md, const Table& t) {
  if (t.rows.empty()) return;
  md << "## " << kTeachingTitle << "\n\n" << kTeachingIntro << "\n\n";
  md_table(md, t);
}

constexpr const char* kEdrTitle = "Error detection and recovery";
constexpr const char* kEdrIntro =
    "Per strategy of a task with model error (cmt edr, Donald 1987; docs/edr.md): whether it is EDR-reliable "
    "(every slice terminates, the goal is reached in some slice, and no termination in the goal is "
    "confusable with a failure termination H of any slice), and per slice of the model parameters the "
    "area where it may end in the goal and in H.";

void md_edr(std::ostream& md, const Table& t, const std::vector<FigureRef>& figures) {
  if (t.rows.empty()) return;
  md << "## " << kEdrTitle << "\n\n" << kEdrIntro << "\n\n";
  md_table(md, t);
  for (const FigureRef& f : figures) md << "![" << md_escape(f.caption) << "](" << f.file << ")\n";
  if (!figures.empty()) md << "\n";
}

constexpr const char* kPlannerTitle = "Planned strategies";
constexpr const char* kPlannerIntro =
    "Per task given to Buckley's planner (cmt plan, ch. 6; docs/planner.md): whether a strategy of spring "
    "motions that stick in the goal was found, its motions (commanded position, the atoms it may stop in, "
    "the "
    "depth of the commanded position inside its set of commanded positions), the verifier's verdict on the "
    "planned strategy from the task's start, and MuJoCo rollouts of it.";

constexpr const char* kExtremesIntro =
    "Buckley's extreme-point experiment (Sec 6.3.4) in simulation (cmt plan --extremes): each planned motion "
    "commanded at every vertex of its set of commanded positions (the planner claims them all, so every "
    "rollout must reach the goal), then at the vertices of the set grown by k eps_p, outside it: how "
    "conservative the planner is.";

void md_planner(std::ostream& md, const ReportContent& c) {
  if (c.planner.rows.empty()) return;
  md << "## " << kPlannerTitle << "\n\n" << kPlannerIntro << "\n\n";
  md_table(md, c.planner);
  for (const FigureRef& f : c.plan_figures) md << "![" << md_escape(f.caption) << "](" << f.file << ")\n";
  if (!c.plan_figures.empty()) md << "\n";
  if (c.extremes.rows.empty()) return;
  md << kExtremesIntro << "\n\n";
  md_table(md, c.extremes);
  for (const FigureRef& f : c.extremes_figures) md << "![" << md_escape(f.caption) << "](" << f.file << ")\n";
  if (!c.extremes_figures.empty()) md << "\n";
}

void md_section(std::ostream& md, const ConfigSection& s) {
  md << "## Config " << s.row->config_id << ": " << md_escape(s.label) << "\n\n";
  if (!s.view_page.empty()) md << "[3-D view](" << s.view_page << ")\n\n";
  md << "Unit `" << md_escape(s.row->unit_key) << "`, status " << s.row->status << ".\n\n";
  for (const std::string& n : s.notes) md << "- " << md_escape(n) << "\n";
  if (!s.notes.empty()) md << "\n";
  for (const FigureRef& f : s.figures) md << "![" << md_escape(f.caption) << "](" << f.file << ")\n";
  if (!s.figures.empty()) md << "\n";
}

// ---- HTML ----

const char* const kStyle = R"css(body { font-family: sans-serif; margin: 1.5em; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border: 1px solid #bbb; padding: 3px 6px; text-align: left; vertical-align: top;
  overflow-wrap: anywhere; }
th { background: #eee; }
code { overflow-wrap: anywhere; }
table.overview { table-layout: fixed; width: 100%; }
table.overview td { vertical-align: middle; }
table.overview a { white-space: nowrap; }
details { margin: 0.5em 0; }
table.summary th, table.details th { width: 12em; }
table.details { max-width: 100%; }
img.thumb { width: 120px; height: auto; border: 1px solid #ddd; display: block; }
section.config { border-top: 2px solid #ccc; margin-top: 1.5em; }
figure { display: inline-block; margin: 0.5em; }
figure img { max-width: 100%; width: 640px; border: 1px solid #ddd; }
)css";

void html_head(std::ostream& h) {
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" << kTitle
    << "</title>\n<style>\n"
    << kStyle << "</style>\n</head>\n<body>\n";
}

void html_summary(std::ostream& h, const ReportContent& c) {
  h << "<h2 id=\"summary\">Summary</h2>\n<table class=\"summary\">\n";
  for (const SummaryLine& line : c.summary)
    h << "<tr><th>" << html_escape(line.label) << "</th><td>" << html_escape(line.text) << "</td></tr>\n";
  h << "</table>\n";
}

void html_runs(std::ostream& h, const ReportContent& c) {
  if (c.runs.empty()) return;
  h << "<details><summary>" << c.runs.size() << " sweep run" << (c.runs.size() == 1 ? "" : "s")
    << "</summary>\n<ul>\n";
  for (const std::string& r : c.runs) h << "<li>" << html_escape(r) << "</li>\n";
  h << "</ul>\n</details>\n";
}

// The overview: fixed layout at the page's width, so long labels wrap instead of widening the table.
// A table's header row and rows, and the closing tag (the caller opened the table).
void html_rows(std::ostream& h, const Table& t) {
  h << "<tr>";
  for (const std::string& head : t.headers) h << "<th>" << html_escape(head) << "</th>";
  h << "</tr>\n";
  for (const auto& row : t.rows) {
    h << "<tr>";
    for (const Cell& cell : row) h << "<td>" << html_cell(cell) << "</td>";
    h << "</tr>\n";
  }
  h << "</table>\n";
}

void html_overview(std::ostream& h, const Table& t) {
  h << "<h2 id=\"overview\">Configurations</h2>\n<table class=\"overview\">\n<colgroup>";
  for (std::size_t k = 0; k < t.headers.size(); ++k) {
    const std::string width = k < t.widths.size() ? t.widths[k] : "";
    h << (width.empty() ? "<col>" : "<col style=\"width: " + width + "\">");
  }
  h << "</colgroup>\n";
  html_rows(h, t);
}

// Every column of the configuration's row of the full table, one per line.
void html_details_table(std::ostream& h, const Table& t, std::size_t row) {
  if (row >= t.rows.size()) return;
  h << "<table class=\"details\">\n";
  for (std::size_t k = 0; k < t.headers.size() && k < t.rows[row].size(); ++k)
    h << "<tr><th>" << html_escape(t.headers[k]) << "</th><td>" << html_cell(t.rows[row][k])
      << "</td></tr>\n";
  h << "</table>\n";
}

void html_falsify(std::ostream& h, const Table& t) {
  if (t.rows.empty()) return;
  h << "<h2 id=\"falsify\">" << kFalsifyTitle << "</h2>\n<p>" << html_escape(kFalsifyIntro)
    << "</p>\n<table class=\"falsify\">\n";
  html_rows(h, t);
}

void html_figures(std::ostream& h, const std::vector<FigureRef>& figures) {
  for (const FigureRef& f : figures)
    h << "<figure><a href=\"" << html_escape(f.file) << "\"><img src=\"" << html_escape(f.file) << "\" alt=\""
      << html_escape(f.caption) << "\"></a><figcaption>" << html_escape(f.caption)
      << "</figcaption></figure>\n";
}

void html_teaching(std::ostream& h, const Table& t) {
  if (t.rows.empty()) return;
  h << "<h2 id=\"teaching\">" << kTeachingTitle << "</h2>\n<p>" << html_escape(kTeachingIntro)
    << "</p>\n<table class=\"teaching\">\n";
  html_rows(h, t);
}

void html_edr(std::ostream& h, const Table& t, const std::vector<FigureRef>& figures) {
  if (t.rows.empty()) return;
  h << "<h2 id=\"edr\">" << kEdrTitle << "</h2>\n<p>" << html_escape(kEdrIntro)
    << "</p>\n<table class=\"edr\">\n";
  html_rows(h, t);
  html_figures(h, figures);
}

void html_planner(std::ostream& h, const ReportContent& c) {
  if (c.planner.rows.empty()) return;
  h << "<h2 id=\"planner\">" << kPlannerTitle << "</h2>\n<p>" << html_escape(kPlannerIntro)
    << "</p>\n<table class=\"planner\">\n";
  html_rows(h, c.planner);
  html_figures(h, c.plan_figures);
  if (c.extremes.rows.empty()) return;
  h << "<p>" << html_escape(kExtremesIntro) << "</p>\n<table class=\"extremes\">\n";
  html_rows(h, c.extremes);
  html_figures(h, c.extremes_figures);
}

void html_section(std::ostream& h, const ReportContent& c, std::size_t i) {
  const ConfigSection& s = c.sections[i];
  h << "<section class=\"config\" id=\"" << section_anchor(*s.row) << "\">\n<h3>Config " << s.row->config_id
    << ": " << html_escape(s.label) << "</h3>\n<p>";
  if (!s.view_page.empty()) h << "<a href=\"" << html_escape(s.view_page) << "\">3-D view</a> | ";
  h << "<a href=\"#overview\">back to the table</a></p>\n";
  h << "<p>Unit <code>" << html_escape(s.row->unit_key) << "</code>, status " << html_escape(s.row->status)
    << ".</p>\n";
  html_details_table(h, c.table, i);
  if (!s.notes.empty()) {
    h << "<ul>\n";
    for (const std::string& n : s.notes) h << "<li>" << html_escape(n) << "</li>\n";
    h << "</ul>\n";
  }
  html_figures(h, s.figures);
  h << "</section>\n";
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string render_markdown(const ReportContent& c) {
  std::ostringstream md;
  md << "# " << kTitle << "\n\n";
  md << "Database: `" << c.database << "`\n\n";
  md_summary(md, c);
  if (!c.runs.empty()) md << "Sweep runs:\n\n";
  for (const std::string& r : c.runs) md << "- " << r << "\n";
  if (!c.runs.empty()) md << "\n";
  md << "## Configurations\n\n";
  md_table(md, c.table);
  md_falsify(md, c.falsify);
  md_teaching(md, c.teaching);
  md_edr(md, c.edr, c.edr_figures);
  md_planner(md, c);
  for (const ConfigSection& s : c.sections) md_section(md, s);
  return md.str();
}

std::string render_html(const ReportContent& c) {
  std::ostringstream h;
  html_head(h);
  h << "<h1>" << kTitle << "</h1>\n<p>Database: <code>" << html_escape(c.database) << "</code></p>\n";
  html_summary(h, c);
  html_runs(h, c);
  html_overview(h, c.overview);
  html_falsify(h, c.falsify);
  html_teaching(h, c.teaching);
  html_edr(h, c.edr, c.edr_figures);
  html_planner(h, c);
  h << "<h2 id=\"details\">Details per configuration</h2>\n";
  for (std::size_t i = 0; i < c.sections.size(); ++i) html_section(h, c, i);
  h << "</body>\n</html>\n";
  return h.str();
}

void write_text_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write the report");
}

}  // namespace cmt::report
