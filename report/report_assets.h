// The browser libraries report.html inlines, read at write time from the Debian packages:
// libjs-three (three.min.js and the OrbitControls.js of its examples, three.js r111) and
// libjs-chart.js (chart.min.js, Chart.js 3.9). Their folder is /usr/share/javascript unless the
// environment variable TISSUEMESH_JS_DIR names another one with the same layout. The page's own
// script and style are compiled in.
#pragma once

#include <string>

namespace tissuemesh {

struct ReportAssets {
  std::string three_js;
  std::string orbit_controls_js;
  std::string chart_js;
  std::string page_js;
  std::string page_css;
};

/// Reads the libraries. Throws OutputError naming the missing file and the packages to install.
/// Every script is checked not to contain "</script", which would end its element early.
ReportAssets load_report_assets();

/// The folder the libraries are read from.
std::string report_js_dir();

}  // namespace tissuemesh
