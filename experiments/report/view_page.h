// Writes a self-contained 3-D page (docs/viewer.md): an HTML file with the view data (view_data.h) embedded,
// and beside it, in an assets folder, three.js and its OrbitControls (Debian's libjs-three, copied so the
// page opens from disk anywhere, with no network) and the page's script (experiments/report/view_assets/,
// compiled into the program).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace cmt::report {

// Where three.min.js and examples/js/controls/OrbitControls.js are read from: $CMT_THREE_JS_DIR when set,
// else /usr/share/javascript/three (Debian package libjs-three).
std::filesystem::path three_js_dir();

// Copies three.min.js, OrbitControls.js and cmt_view.js into `assets_dir`. Throws std::runtime_error naming
// the missing file and the package to install, or the file that cannot be written.
void write_view_assets(const std::filesystem::path& assets_dir);

// The page itself; `assets_rel` is the assets folder relative to the HTML file ("." or "view_assets").
// Throws std::runtime_error when the file cannot be written.
void write_view_page(const nlohmann::json& data, const std::filesystem::path& html_file,
                     const std::string& assets_rel);

}  // namespace cmt::report
