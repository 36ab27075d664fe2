// Reading the text of a YAML input file (task file, sweep spec) into one document, with bad-input errors in
// the TaskError style: a syntax error names its line and column and the key path it sits under; nesting
// beyond yaml-cpp's depth limit and a second document after `---` are rejected by name (a second document
// would otherwise be ignored without a word).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

namespace cmt {

// The single document of `text`; an empty text gives a null node. Throws TaskError(file_label, ...).
YAML::Node load_yaml_document(const std::string& text, const std::string& file_label);

// The 1-based line where a second YAML document starts (a "---" marker after the first document began, or
// content after a "..." end marker), 0 when the text holds at most one document.
int second_document_line(const std::string& text);

// The block-style key path (keys joined by '.', list indices left out) that encloses 1-based `line` of
// `text`, read from indentation alone, so that it works on text that does not parse. Empty at top level.
std::string enclosing_key_path(const std::string& text, int line);

}  // namespace cmt
