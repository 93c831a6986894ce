#include "render/text.hpp"

#include <charconv>
#include <filesystem>

namespace plyfit::exporters::render {

std::string exact_text(double x) {
  if (x == 0.0) return "0";  // also -0
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof(buf), x, std::chars_format::fixed);
  if (r.ec != std::errc()) {  // beyond 512 characters: fall back to the shortest general form
    const auto g = std::to_chars(buf, buf + sizeof(buf), x);
    return std::string(buf, g.ptr);
  }
  return std::string(buf, r.ptr);
}

std::string fixed_text(double x, int decimals) {
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof(buf), x, std::chars_format::fixed, decimals);
  std::string s(buf, r.ec == std::errc() ? r.ptr : buf);
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0" || s.empty()) return std::string(1, '0');
  return s;
}

std::string degrees_text(double deg, int decimals) {
  return fixed_text(deg, decimals) + "\u00b0";
}

namespace {

// One UTF-8 sequence at s[k]: its code point and length, or length 0 when it is invalid
// (a stray or missing continuation byte, an overlong form, a surrogate, past U+10FFFF).
struct Utf8Char {
  char32_t cp = 0;
  int len = 0;
};
Utf8Char utf8_at(const std::string& s, std::size_t k) {
  const auto b0 = static_cast<unsigned char>(s[k]);
  Utf8Char c;
  if (b0 < 0x80) return {b0, 1};
  if ((b0 & 0xE0) == 0xC0) {
    c = {static_cast<char32_t>(b0 & 0x1F), 2};
  } else if ((b0 & 0xF0) == 0xE0) {
    c = {static_cast<char32_t>(b0 & 0x0F), 3};
  } else if ((b0 & 0xF8) == 0xF0) {
    c = {static_cast<char32_t>(b0 & 0x07), 4};
  } else {
    return {};
  }
  if (k + static_cast<std::size_t>(c.len) > s.size()) return {};
  for (int m = 1; m < c.len; ++m) {
    const auto b = static_cast<unsigned char>(s[k + static_cast<std::size_t>(m)]);
    if ((b & 0xC0) != 0x80) return {};
    c.cp = (c.cp << 6) | (b & 0x3F);
  }
  static constexpr char32_t kMinForLength[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (c.cp < kMinForLength[c.len] || c.cp > 0x10FFFF || (c.cp >= 0xD800 && c.cp <= 0xDFFF))
    return {};
  return c;
}

}  // namespace

std::u32string utf8_decode(const std::string& s) {
  constexpr char32_t kReplacement = 0xFFFD;
  std::u32string out;
  for (std::size_t k = 0; k < s.size();) {
    const Utf8Char c = utf8_at(s, k);
    if (c.len == 0) {
      out += kReplacement;
      ++k;
      continue;
    }
    out += c.cp;
    k += static_cast<std::size_t>(c.len);
  }
  return out;
}

std::string utf8_encode(const std::u32string& s) {
  std::string o;
  for (const char32_t c : s) {
    if (c < 0x80) {
      o += static_cast<char>(c);
    } else if (c < 0x800) {
      o += static_cast<char>(0xC0 | (c >> 6));
      o += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      o += static_cast<char>(0xE0 | (c >> 12));
      o += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      o += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      o += static_cast<char>(0xF0 | (c >> 18));
      o += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      o += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      o += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return o;
}

std::size_t utf8_length(const std::string& s) {
  return utf8_decode(s).size();
}

std::string xml_escape(const std::string& s) {
  std::u32string clean;
  for (const char32_t c : utf8_decode(s)) {
    // Control characters are not allowed in XML 1.0 (tab and newline are, but a label has no
    // use for them); neither are U+FFFE and U+FFFF.
    if (c < 0x20 || c == 0x7F || c == 0xFFFE || c == 0xFFFF)
      clean += U' ';
    else
      clean += c;
  }
  std::string o;
  for (const char ch : utf8_encode(clean)) {
    switch (ch) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      case '\'':
        o += "&apos;";
        break;
      default:
        o += ch;
    }
  }
  return o;
}

std::vector<std::string> wrap_words(const std::string& s, std::size_t max_chars) {
  std::vector<std::string> lines;
  std::string line, word;
  std::size_t line_len = 0;
  auto flush_word = [&] {
    if (word.empty()) return;
    const std::size_t n = utf8_length(word);
    if (line_len > 0 && line_len + 1 + n > max_chars) {
      lines.push_back(line);
      line.clear();
      line_len = 0;
    }
    if (line_len > 0) {
      line += ' ';
      ++line_len;
    }
    line += word;
    line_len += n;
    word.clear();
  };
  for (const char c : s) {
    if (c == ' ')
      flush_word();
    else
      word += c;
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string mold_label(const std::string& mold) {
  if (mold.rfind("builtin:", 0) == 0) return mold;
  const std::string name = std::filesystem::path(mold).filename().string();
  return name.empty() ? mold : name;
}

std::string faces_label(const std::vector<int>& faces) {
  constexpr std::size_t kListedFaces = 6;  // more are counted, not listed
  if (faces.size() <= 1) return "face " + std::to_string(faces.empty() ? 0 : faces.front());
  if (faces.size() > kListedFaces) return std::to_string(faces.size()) + " faces";
  std::string out = "faces ";
  for (std::size_t k = 0; k < faces.size(); ++k) out += (k ? ", " : "") + std::to_string(faces[k]);
  return out;
}

std::string material_label(const ExportContext& ctx) {
  return ctx.options.material_label.empty() ? ctx.run.material : ctx.options.material_label;
}

}  // namespace plyfit::exporters::render
