// Renders the report content (report_table.h) as report.md (GitHub-flavoured Markdown) and index.html (one
// self-contained page; figures are linked PNG files next to it).
#pragma once

#include <filesystem>
#include <string>

#include "experiments/report/report_table.h"

namespace cmt::report {

std::string render_markdown(const ReportContent& content);
std::string render_html(const ReportContent& content);

// Writes text to a file; throws std::runtime_error naming the file when it cannot.
void write_text_file(const std::filesystem::path& file, const std::string& text);

}  // namespace cmt::report
