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

std::string md_cell(const Cell& cell) {
  std::string out;
  for (const Span& s : cell) {
    if (!out.empty()) out += ' ';
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
  }
  return out;
}

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

std::string html_cell(const Cell& cell) {
  std::string out;
  for (const Span& s : cell) {
    if (!out.empty()) out += ' ';
    if (!s.href.empty())
      out += "<a href=\"" + html_escape(s.href) + "\">" + html_escape(s.text) + "</a>";
    else if (s.code)
      out += "<code>" + html_escape(s.text) + "</code>";
    else
      out += html_escape(s.text);
  }
  return out;
}

std::string anchor(const ConfigSection& s) { return "config-" + std::to_string(s.row->config_id); }

}  // namespace

std::string render_markdown(const ReportContent& c) {
  std::ostringstream md;
  md << "# " << kTitle << "\n\n";
  md << "Database: `" << c.database << "`\n\n";
  for (const std::string& r : c.runs) md << "- " << r << "\n";
  if (!c.runs.empty()) md << "\n";
  md << "**Summary:** " << c.summary << "\n\n";
  md << "## Configurations\n\n|";
  for (const std::string& h : c.table.headers) md << " " << md_escape(h) << " |";
  md << "\n|";
  for (std::size_t i = 0; i < c.table.headers.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& row : c.table.rows) {
    md << "|";
    for (const Cell& cell : row) md << " " << md_cell(cell) << " |";
    md << "\n";
  }
  md << "\n";
  for (const ConfigSection& s : c.sections) {
    md << "## Config " << s.row->config_id << ": " << md_escape(s.label) << "\n\n";
    md << "Unit `" << md_escape(s.row->unit_key) << "`, status " << s.row->status << ".\n\n";
    for (const std::string& n : s.notes) md << "- " << md_escape(n) << "\n";
    if (!s.notes.empty()) md << "\n";
    for (const FigureRef& f : s.figures) md << "![" << md_escape(f.caption) << "](" << f.file << ")\n";
    if (!s.figures.empty()) md << "\n";
  }
  return md.str();
}

std::string render_html(const ReportContent& c) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << kTitle
    << "</title>\n<style>\n"
    << "body { font-family: sans-serif; margin: 1.5em; }\n"
    << "table { border-collapse: collapse; font-size: 0.85em; }\n"
    << "th, td { border: 1px solid #bbb; padding: 3px 6px; text-align: left; vertical-align: top; }\n"
    << "th { background: #eee; }\n"
    << "figure { display: inline-block; margin: 0.5em; }\n"
    << "img { max-width: 100%; width: 640px; border: 1px solid #ddd; }\n"
    << "</style>\n</head>\n<body>\n";
  h << "<h1>" << kTitle << "</h1>\n<p>Database: <code>" << html_escape(c.database) << "</code></p>\n";
  if (!c.runs.empty()) {
    h << "<ul>\n";
    for (const std::string& r : c.runs) h << "<li>" << html_escape(r) << "</li>\n";
    h << "</ul>\n";
  }
  h << "<p><strong>Summary:</strong> " << html_escape(c.summary) << "</p>\n";
  h << "<h2>Configurations</h2>\n<table>\n<tr>";
  for (const std::string& head : c.table.headers) h << "<th>" << html_escape(head) << "</th>";
  h << "</tr>\n";
  for (std::size_t i = 0; i < c.table.rows.size(); ++i) {
    h << "<tr>";
    for (std::size_t k = 0; k < c.table.rows[i].size(); ++k) {
      const std::string cell = html_cell(c.table.rows[i][k]);
      // The config id links to its section.
      if (k == 0 && i < c.sections.size())
        h << "<td><a href=\"#" << anchor(c.sections[i]) << "\">" << cell << "</a></td>";
      else
        h << "<td>" << cell << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table>\n";
  for (const ConfigSection& s : c.sections) {
    h << "<h2 id=\"" << anchor(s) << "\">Config " << s.row->config_id << ": " << html_escape(s.label)
      << "</h2>\n";
    h << "<p>Unit <code>" << html_escape(s.row->unit_key) << "</code>, status " << html_escape(s.row->status)
      << ".</p>\n";
    if (!s.notes.empty()) {
      h << "<ul>\n";
      for (const std::string& n : s.notes) h << "<li>" << html_escape(n) << "</li>\n";
      h << "</ul>\n";
    }
    for (const FigureRef& f : s.figures)
      h << "<figure><a href=\"" << html_escape(f.file) << "\"><img src=\"" << html_escape(f.file)
        << "\" alt=\"" << html_escape(f.caption) << "\"></a><figcaption>" << html_escape(f.caption)
        << "</figcaption></figure>\n";
  }
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
