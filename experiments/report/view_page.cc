#include "experiments/report/view_page.h"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "experiments/common/json_text.h"
#include "experiments/report/report_documents.h"

namespace cmt::report {

extern const char* const kViewScript;  // view_assets.cc, generated from view_assets/cmt_view.js

namespace {

constexpr const char* kStyle = R"css(
html, body { margin: 0; height: 100%; overflow: hidden; font: 13px/1.35 system-ui, sans-serif; color: #1f2933; }
#page { display: flex; height: 100%; }
#panel { width: 290px; flex: none; overflow-y: auto; padding: 10px 12px; box-sizing: border-box;
         border-right: 1px solid #d9e2ec; background: #f8fafc; }
#view { flex: 1; min-width: 0; position: relative; overflow: hidden; }
#view canvas { display: block; }
#title { font-weight: 600; font-size: 15px; margin-bottom: 2px; }
#units, #help { color: #52606d; margin-bottom: 8px; }
#layers { list-style: none; padding: 0; margin: 0 0 10px 0; }
#layers li { padding: 1px 0 1px 16px; }
#layers li.group { padding-left: 0; margin-top: 6px; font-weight: 600; }
.swatch { display: inline-block; width: 10px; height: 10px; margin: 0 4px 0 2px; border: 1px solid #0003; }
#info { border-top: 1px solid #d9e2ec; padding-top: 6px; word-break: break-word; }
.info-title { font-weight: 600; }
#errors { color: #b00020; white-space: pre-wrap; }
#status { display: none; }
)css";

void copy_library_file(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (!std::filesystem::exists(from))
    throw std::runtime_error(from.string() +
                             ": three.js not found (install the Debian package libjs-three, or set "
                             "CMT_THREE_JS_DIR to a folder holding three.min.js and "
                             "examples/js/controls/OrbitControls.js)");
  std::error_code ec;
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing, ec);
  if (ec) throw std::runtime_error(to.string() + ": cannot write: " + ec.message());
}

// JSON inside <script>: "</" would end the element, so it is written "<\/" (the same string in JSON).
std::string script_safe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

}  // namespace

std::filesystem::path three_js_dir() {
  const char* dir = std::getenv("CMT_THREE_JS_DIR");
  return dir && *dir ? std::filesystem::path(dir) : std::filesystem::path("/usr/share/javascript/three");
}

void write_view_assets(const std::filesystem::path& assets_dir) {
  std::error_code ec;
  std::filesystem::create_directories(assets_dir, ec);
  if (ec) throw std::runtime_error(assets_dir.string() + ": cannot create: " + ec.message());
  const std::filesystem::path three = three_js_dir();
  copy_library_file(three / "three.min.js", assets_dir / "three.min.js");
  copy_library_file(three / "examples/js/controls/OrbitControls.js", assets_dir / "OrbitControls.js");
  write_text_file(assets_dir / "cmt_view.js", kViewScript);
}

void write_view_page(const nlohmann::json& data, const std::filesystem::path& html_file,
                     const std::string& assets_rel) {
  const std::string title = html_escape(data.value("title", std::string("cmt view")));
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + title +
      " (3-D)</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<div id=\"page\">\n" +
      "<div id=\"panel\">\n<div id=\"title\"></div>\n<div id=\"units\"></div>\n" +
      "<div id=\"help\">Drag to turn, wheel to zoom, right-drag to pan. Click a piece for "
      "its details. Predicted pieces: solid where the atom must stick, lighter where it may, faint where it "
      "never sticks (a slow stop, sensing or the contact lift puts it there).</div>\n<ul "
      "id=\"layers\"></ul>\n<div id=\"info\"></div>\n"
      "<div id=\"errors\" data-count=\"0\" hidden></div>\n<div id=\"status\">loading</div>\n"
      "</div>\n<div id=\"view\"></div>\n</div>\n<script>window.CMT_VIEW_DATA = " +
      script_safe(json_text(data)) + ";</script>\n";
  for (const char* file : {"three.min.js", "OrbitControls.js", "cmt_view.js"})
    html += "<script src=\"" + html_escape(assets_rel) + "/" + file + "\"></script>\n";
  html += "</body>\n</html>\n";
  write_text_file(html_file, html);
}

}  // namespace cmt::report
