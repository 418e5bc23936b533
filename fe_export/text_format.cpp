#include "fe_export/text_format.h"

#include <charconv>
#include <cstdint>
#include <sstream>

namespace tissuemesh {

namespace {

/// Decodes one UTF-8 code point at s[i] (advancing i); an invalid byte is taken as Latin-1.
std::uint32_t next_code_point(const std::string& s, std::size_t& i) {
  const auto b = static_cast<unsigned char>(s[i]);
  int len = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 0;
  if (len == 0 || i + len > s.size()) return ++i, b;
  std::uint32_t cp = len == 1 ? b : b & (0x7F >> len);
  for (int k = 1; k < len; ++k) {
    const auto c = static_cast<unsigned char>(s[i + k]);
    if ((c >> 6) != 0x2) return ++i, b;
    cp = (cp << 6) | (c & 0x3F);
  }
  i += len;
  return cp;
}

bool xml_char(std::uint32_t cp) {
  return cp == 0x9 || cp == 0xA || cp == 0xD || (cp >= 0x20 && cp <= 0xD7FF) || (cp >= 0xE000 && cp <= 0xFFFD) ||
         (cp >= 0x10000 && cp <= 0x10FFFF);
}

}  // namespace

std::string shortest_decimal(double v) {
  if (v == 0.0) return "0";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const std::uint32_t cp = next_code_point(s, i);
    switch (cp) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (!xml_char(cp)) out += '?';
        else if (cp < 0x80) out += static_cast<char>(cp);
        else {
          std::ostringstream ref;
          ref << "&#x" << std::hex << std::uppercase << cp << ';';
          out += ref.str();
        }
    }
  }
  return out;
}

std::string xml_comment(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const std::uint32_t cp = next_code_point(s, i);
    const char c = (cp >= 0x20 && cp < 0x7F) ? static_cast<char>(cp) : (cp == '\t' || cp == '\n' ? ' ' : '?');
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

}  // namespace tissuemesh
