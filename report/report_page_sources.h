// report.html's own script and style (report/page/report.js, report/page/report.css), compiled
// into the library by CMake (report/CMakeLists.txt) so that the program needs no data files.
#pragma once

namespace tissuemesh {
extern const char kReportPageJs[];
extern const char kReportPageCss[];
}  // namespace tissuemesh
