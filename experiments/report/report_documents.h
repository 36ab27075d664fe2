// Renders the report content (report_table.h) as report.md (GitHub-flavoured Markdown: the summary, the full
// table, then a section per configuration) and index.html (one self-contained page; figures are linked PNG
// files next to it). The HTML page opens on the summary and the overview table, which fit a 1400 px window;
// below them one anchored section per configuration ("#config-<id>") holds every column of the full table
// as a two-column table, the notes and the figures.
#pragma once

#include <filesystem>
#include <string>

#include "experiments/report/report_table.h"

namespace cmt::report {

std::string render_markdown(const ReportContent& content);
std::string render_html(const ReportContent& content);

// `&`, `<`, `>` and `"` as HTML entities (text and attribute values).
std::string html_escape(const std::string& text);

// Writes text to a file; throws std::runtime_error naming the file when it cannot.
void write_text_file(const std::filesystem::path& file, const std::string& text);

}  // namespace cmt::report
