#include "report/report_assets.h"

#include "core/errors.h"
#include "report/report_page_sources.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace tissuemesh {

namespace {
std::string read_script(const std::string& path, const char* package) {
  std::ifstream f(path, std::ios::binary);
  if (!f)
    throw OutputError("report.html needs " + path + " (Debian package " + package +
                      "; scripts/setup.sh installs it), or run with --no-html");
  std::ostringstream s;
  s << f.rdbuf();
  std::string text = s.str();
  if (text.find("</script") != std::string::npos)
    throw OutputError(path + " contains \"</script\" and cannot be inlined into report.html");
  return text;
}
}  // namespace

std::string report_js_dir() {
  const char* env = std::getenv("TISSUEMESH_JS_DIR");
  return env && *env ? std::string(env) : std::string("/usr/share/javascript");
}

ReportAssets load_report_assets() {
  const std::string dir = report_js_dir();
  ReportAssets a;
  a.three_js = read_script(dir + "/three/three.min.js", "libjs-three");
  a.orbit_controls_js = read_script(dir + "/three/examples/js/controls/OrbitControls.js", "libjs-three");
  a.chart_js = read_script(dir + "/chart.js/chart.min.js", "libjs-chart.js");
  a.page_js = kReportPageJs;
  a.page_css = kReportPageCss;
  return a;
}

}  // namespace tissuemesh
