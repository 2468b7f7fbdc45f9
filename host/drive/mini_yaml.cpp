// The YAML subset of mini_yaml.h, by recursive descent over the lines. The cursor is a line and a
// column: a block starts where its first content is; "- " moves the column past the dash, so
// that an item's content ("- key: v", "- - x") is read as a block starting at that column.
#include "host/drive/mini_yaml.h"

#include <cstdint>
#include <string_view>

namespace lpir {

const YamlNode* YamlNode::Get(const std::string& key) const {
  if (kind != Kind::kMap) return nullptr;
  for (const auto& [k, v] : map)
    if (k == key) return &v;
  return nullptr;
}

namespace {

constexpr int kMaxDepth = 64;

bool IsSpace(char c) { return c == ' ' || c == '\t'; }

// `code` as UTF-8 (YamlError for one past U+10FFFF).
void AppendUtf8(uint32_t code, int line, std::string* out) {
  if (code < 0x80) {
    *out += char(code);
  } else if (code < 0x800) {
    *out += char(0xC0 | code >> 6);
    *out += char(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    *out += char(0xE0 | code >> 12);
    *out += char(0x80 | (code >> 6 & 0x3F));
    *out += char(0x80 | (code & 0x3F));
  } else if (code < 0x110000) {
    *out += char(0xF0 | code >> 18);
    *out += char(0x80 | (code >> 12 & 0x3F));
    *out += char(0x80 | (code >> 6 & 0x3F));
    *out += char(0x80 | (code & 0x3F));
  } else {
    throw YamlError("line " + std::to_string(line) + ": escape past U+10FFFF");
  }
}

class Parser {
 public:
  explicit Parser(const std::string& text) {
    size_t start = 0;
    while (start <= text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(std::move(line));
      start = end + 1;
    }
    StartLine(0);
  }

  YamlNode Document() {
    if (SkipBlank() && Rest().substr(0, 3) == "---" && (Rest().size() == 3 || IsSpace(Rest()[3]))) {
      col_ += 3;
      ExpectLineEnd();
    }
    YamlNode root = Block(0, 0);
    if (SkipBlank() && !(Rest().substr(0, 3) == "..." && (Rest().size() == 3))) {
      Fail("unexpected content (an indentation this reader cannot place)");
    }
    return root;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const { FailAt(int(line_) + 1, what); }
  [[noreturn]] static void FailAt(int line, const std::string& what) {
    throw YamlError("line " + std::to_string(line) + ": " + what);
  }

  bool AtEnd() const { return line_ >= lines_.size(); }
  std::string_view Rest() const {
    if (AtEnd()) return {};
    return std::string_view(lines_[line_]).substr(std::min(col_, lines_[line_].size()));
  }
  int Line() const { return int(line_) + 1; }

  // The cursor at line `l`'s first character that is not a space; a tab before it is an error.
  void StartLine(size_t l) {
    line_ = l;
    col_ = 0;
    if (AtEnd()) return;
    const std::string& s = lines_[l];
    while (col_ < s.size() && IsSpace(s[col_])) {
      if (s[col_] == '\t') {
        const size_t content = s.find_first_not_of(" \t");
        if (content != std::string::npos && s[content] != '#') Fail("a tab in the indentation");
      }
      ++col_;
    }
  }
  // Past blank lines and comments; false at the end of the text.
  bool SkipBlank() {
    while (!AtEnd()) {
      const std::string_view rest = Rest();
      size_t k = 0;
      while (k < rest.size() && IsSpace(rest[k])) ++k;
      if (k < rest.size() && rest[k] != '#') {
        col_ += k;
        return true;
      }
      StartLine(line_ + 1);
    }
    return false;
  }
  // Nothing but spaces and a comment left on the line; the cursor moves to the next line.
  void ExpectLineEnd() {
    const std::string_view rest = Rest();
    size_t k = 0;
    while (k < rest.size() && IsSpace(rest[k])) ++k;
    if (k < rest.size() && rest[k] != '#') Fail("unexpected '" + std::string(rest.substr(k)) + "'");
    StartLine(line_ + 1);
  }

  static bool IsDash(std::string_view rest) {
    return !rest.empty() && rest[0] == '-' && (rest.size() == 1 || IsSpace(rest[1]));
  }
  // Where the ':' of a mapping key on `rest` is (npos: no key here).
  static size_t KeyColon(std::string_view rest) {
    size_t k = 0;
    if (!rest.empty() && (rest[0] == '"' || rest[0] == '\'')) {
      const char quote = rest[0];
      for (k = 1; k < rest.size(); ++k) {
        if (quote == '"' && rest[k] == '\\') {
          ++k;
        } else if (rest[k] == quote) {
          if (quote == '\'' && k + 1 < rest.size() && rest[k + 1] == '\'') {
            ++k;
            continue;
          }
          break;
        }
      }
      ++k;
      while (k < rest.size() && IsSpace(rest[k])) ++k;
      return k < rest.size() && rest[k] == ':' && (k + 1 == rest.size() || IsSpace(rest[k + 1]))
                 ? k
                 : std::string_view::npos;
    }
    for (; k < rest.size(); ++k) {
      if (rest[k] == '#' && k > 0 && IsSpace(rest[k - 1])) break;
      if (rest[k] == ':' && (k + 1 == rest.size() || IsSpace(rest[k + 1]))) return k;
    }
    return std::string_view::npos;
  }

  // The block whose first content is at or right of `min_col` (null when the next content lies
  // left of it, or at the end).
  YamlNode Block(size_t min_col, int depth) {
    CheckDepth(depth);
    if (!SkipBlank() || col_ < min_col) return YamlNode{};
    const std::string_view rest = Rest();
    if (IsDash(rest)) return Sequence(col_, depth);
    if (KeyColon(rest) != std::string_view::npos) return Mapping(col_, depth);
    return InlineValue(int(min_col) - 1);
  }

  void CheckDepth(int depth) const {
    if (depth > kMaxDepth) Fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
  }

  YamlNode Sequence(size_t col, int depth) {
    CheckDepth(depth);
    YamlNode node;
    node.kind = YamlNode::Kind::kSeq;
    node.line = Line();
    while (SkipBlank() && col_ == col && IsDash(Rest())) {
      ++col_;  // past the dash
      const std::string_view rest = Rest();
      size_t k = 0;
      while (k < rest.size() && IsSpace(rest[k])) ++k;
      if (k == rest.size() || rest[k] == '#') {
        StartLine(line_ + 1);
        node.seq.push_back(Block(col + 1, depth + 1));
        continue;
      }
      col_ += k;
      const std::string_view item = Rest();
      if (IsDash(item)) {
        node.seq.push_back(Sequence(col_, depth + 1));
      } else if (KeyColon(item) != std::string_view::npos) {
        node.seq.push_back(Mapping(col_, depth + 1));
      } else {
        node.seq.push_back(InlineValue(int(col)));
      }
    }
    if (!AtEnd() && col_ > col) Fail("an indentation that belongs to no item");
    return node;
  }

  YamlNode Mapping(size_t col, int depth) {
    CheckDepth(depth);
    YamlNode node;
    node.kind = YamlNode::Kind::kMap;
    node.line = Line();
    while (SkipBlank() && col_ >= col) {
      if (col_ > col) Fail("an indentation that belongs to no key");
      const std::string_view rest = Rest();
      if (IsDash(rest)) break;  // the caller's sequence, or an error there
      const size_t colon = KeyColon(rest);
      if (colon == std::string_view::npos) Fail("a line that is no 'key: value'");
      std::string key = std::string(rest.substr(0, colon));
      while (!key.empty() && IsSpace(key.back())) key.pop_back();
      if (!key.empty() && (key[0] == '"' || key[0] == '\'')) {
        Parser quoted(key);
        key = quoted.Block(0, depth + 1).scalar;
      }
      for (const auto& entry : node.map)
        if (entry.first == key) Fail("key '" + key + "' given twice");
      const int key_line = Line();
      col_ += colon + 1;
      const std::string_view after = Rest();
      size_t k = 0;
      while (k < after.size() && IsSpace(after[k])) ++k;
      YamlNode value;
      if (k == after.size() || after[k] == '#') {
        StartLine(line_ + 1);
        if (SkipBlank() && col_ > col) {
          value = Block(col + 1, depth + 1);
        } else if (!AtEnd() && col_ == col && IsDash(Rest())) {
          value = Sequence(col, depth + 1);  // "key:\n- item": PyYAML's sequences
        }
      } else {
        col_ += k;
        value = InlineValue(int(col));
      }
      if (value.line == 0) value.line = key_line;
      node.map.emplace_back(std::move(key), std::move(value));
    }
    return node;
  }

  // A scalar or flow collection starting at the cursor; its continuation lines must be indented
  // past `parent` (the column of the key or dash it belongs to). The cursor ends on the next line.
  YamlNode InlineValue(int parent) {
    YamlNode node;
    node.line = Line();
    const std::string_view rest = Rest();
    const char c = rest[0];
    if (c == '"' || c == '\'') {
      node.kind = YamlNode::Kind::kScalar;
      node.scalar = Quoted(c);
      ExpectLineEnd();
      return node;
    }
    if (c == '[') return FlowSequence();
    if (c == '{') {
      size_t k = 1;
      while (k < rest.size() && IsSpace(rest[k])) ++k;
      if (k == rest.size() || rest[k] != '}') Fail("a flow mapping with content");
      col_ += k + 1;
      ExpectLineEnd();
      node.kind = YamlNode::Kind::kMap;
      return node;
    }
    if (c == '|' || c == '>') {
      node.kind = YamlNode::Kind::kScalar;
      node.scalar = BlockScalar(parent);
      return node;
    }
    if (c == '&' || c == '*' || c == '!' || c == '%' || c == '@' || c == '`') {
      Fail(std::string("'") + c + "': anchors, aliases, tags and directives are not read");
    }
    if ((c == '?' || c == ':') && (rest.size() == 1 || IsSpace(rest[1]))) {
      Fail(std::string("'") + c + "': explicit keys are not read");
    }
    // A plain scalar: this line to a comment, then the more indented lines that follow.
    std::string text = PlainPart(rest);
    StartLine(line_ + 1);
    size_t blank = 0;
    while (!AtEnd()) {
      const std::string_view more = Rest();
      if (more.empty()) {
        ++blank;
        StartLine(line_ + 1);
        continue;
      }
      if (int(col_) <= parent || more[0] == '#') break;
      text += blank ? std::string(blank, '\n') : std::string(" ");
      text += PlainPart(more);
      blank = 0;
      StartLine(line_ + 1);
    }
    if (text.empty() || text == "~" || text == "null" || text == "Null" || text == "NULL") {
      return node;  // null
    }
    node.kind = YamlNode::Kind::kScalar;
    node.scalar = std::move(text);
    return node;
  }

  // `s` up to a comment, without the spaces around it.
  static std::string PlainPart(std::string_view s) {
    size_t end = s.size();
    for (size_t k = 0; k < s.size(); ++k)
      if (s[k] == '#' && (k == 0 || IsSpace(s[k - 1]))) {
        end = k;
        break;
      }
    size_t begin = 0;
    while (begin < end && IsSpace(s[begin])) ++begin;
    while (end > begin && IsSpace(s[end - 1])) --end;
    return std::string(s.substr(begin, end - begin));
  }

  // "[a, 'b', \"c\"]" on one line: a sequence of scalars.
  YamlNode FlowSequence() {
    YamlNode node;
    node.kind = YamlNode::Kind::kSeq;
    node.line = Line();
    ++col_;  // '['
    for (;;) {
      std::string_view rest = Rest();
      size_t k = 0;
      while (k < rest.size() && IsSpace(rest[k])) ++k;
      col_ += k;
      rest = Rest();
      if (rest.empty()) Fail("a flow sequence that does not end on its line");
      if (rest[0] == ']') {
        if (!node.seq.empty()) Fail("a flow sequence ending in ','");
        ++col_;
        break;
      }
      YamlNode item;
      item.kind = YamlNode::Kind::kScalar;
      item.line = Line();
      if (rest[0] == '"' || rest[0] == '\'') {
        const size_t line = line_;
        item.scalar = Quoted(rest[0]);
        if (line_ != line) Fail("a flow sequence item over several lines");
      } else if (rest[0] == '[' || rest[0] == '{') {
        Fail("a nested flow collection");
      } else {
        size_t end = 0;
        while (end < rest.size() && rest[end] != ',' && rest[end] != ']') ++end;
        item.scalar = PlainPart(rest.substr(0, end));
        col_ += end;
      }
      node.seq.push_back(std::move(item));
      rest = Rest();
      k = 0;
      while (k < rest.size() && IsSpace(rest[k])) ++k;
      col_ += k;
      rest = Rest();
      if (!rest.empty() && rest[0] == ',') {
        ++col_;
        continue;
      }
      if (!rest.empty() && rest[0] == ']') {
        ++col_;
        break;
      }
      Fail("a flow sequence item not followed by ',' or ']'");
    }
    ExpectLineEnd();
    return node;
  }

  // A quoted scalar from the cursor (at its opening quote) to its closing quote, over as many
  // lines as it takes; the cursor ends after the closing quote.
  std::string Quoted(char quote) {
    const int first = Line();
    std::string out;
    size_t kept = 0;  // out's length without the spaces a line break would drop
    ++col_;
    for (;;) {
      if (AtEnd())
        FailAt(first, std::string("a ") + (quote == '"' ? "double" : "single") +
                          "-quoted scalar that never ends");
      const std::string& s = lines_[line_];
      bool escaped_break = false;
      while (col_ < s.size()) {
        const char c = s[col_++];
        if (c == quote) {
          if (quote == '\'' && col_ < s.size() && s[col_] == '\'') {
            out += '\'';
            ++col_;
            kept = out.size();
            continue;
          }
          return out;
        }
        if (quote == '"' && c == '\\') {
          if (col_ == s.size()) {
            escaped_break = true;
            break;
          }
          Escape(s, &out);
          kept = out.size();
          continue;
        }
        out += c;
        if (!IsSpace(c)) kept = out.size();
      }
      // A line break inside the scalar: an escaped one joins the lines; else the spaces before
      // it go and it folds into a space, or into a '\n' per blank line after it. The next line's
      // leading spaces go either way.
      size_t next = line_ + 1, blank = 0;
      while (next < lines_.size() && lines_[next].find_first_not_of(" \t") == std::string::npos) {
        ++blank, ++next;
      }
      if (!escaped_break) {
        out.resize(kept);
        if (!blank) out += ' ';
      }
      out += std::string(blank, '\n');
      kept = out.size();
      line_ = next;
      col_ = 0;
      if (!AtEnd()) {
        const std::string& n = lines_[line_];
        while (col_ < n.size() && IsSpace(n[col_])) ++col_;
      }
    }
  }

  // One escape after a '\\' of a double-quoted scalar (the cursor past the backslash).
  void Escape(const std::string& s, std::string* out) {
    const char e = s[col_++];
    auto hex = [&](int digits) {
      if (s.size() - col_ < size_t(digits)) Fail("a \\x, \\u or \\U escape cut short");
      uint32_t code = 0;
      for (int d = 0; d < digits; ++d) {
        const char h = s[col_++];
        code <<= 4;
        if (h >= '0' && h <= '9') {
          code |= uint32_t(h - '0');
        } else if (h >= 'a' && h <= 'f') {
          code |= uint32_t(h - 'a' + 10);
        } else if (h >= 'A' && h <= 'F') {
          code |= uint32_t(h - 'A' + 10);
        } else {
          Fail(std::string("'") + h + "' in a hexadecimal escape");
        }
      }
      AppendUtf8(code, Line(), out);
    };
    // YAML 1.2's one-character escapes and what they stand for
    static const std::pair<char, uint32_t> kEscapes[] = {
        {'0', 0},   {'a', 7},     {'b', 8},    {'t', 9},    {'\t', 9},     {'n', 10},
        {'v', 11},  {'f', 12},    {'r', 13},   {'e', 27},   {' ', ' '},    {'"', '"'},
        {'/', '/'}, {'\\', '\\'}, {'N', 0x85}, {'_', 0xA0}, {'L', 0x2028}, {'P', 0x2029}};
    for (const auto& [name, code] : kEscapes) {
      if (e == name) {
        AppendUtf8(code, Line(), out);
        return;
      }
    }
    if (e == 'x' || e == 'u' || e == 'U') {
      hex(e == 'x' ? 2 : e == 'u' ? 4 : 8);
      return;
    }
    Fail(std::string("unknown escape '\\") + e + "'");
  }

  // A literal (|) or folded (>) block scalar: its header at the cursor, its lines those after it
  // indented past `parent` (or blank).
  std::string BlockScalar(int parent) {
    const std::string_view header = Rest();
    const bool folded = header[0] == '>';
    char chomp = 0;
    size_t indent = 0;
    size_t k = 1;
    for (; k < header.size() && !IsSpace(header[k]); ++k) {
      if ((header[k] == '-' || header[k] == '+') && !chomp) {
        chomp = header[k];
      } else if (header[k] >= '1' && header[k] <= '9' && !indent) {
        indent = size_t(parent + 1) + size_t(header[k] - '0') - 1;
      } else {
        Fail("a block scalar header other than |, >, with - or + and an indentation digit");
      }
    }
    col_ += k;
    ExpectLineEnd();
    std::vector<std::string> lines;
    while (!AtEnd()) {
      const std::string& s = lines_[line_];
      const size_t content = s.find_first_not_of(' ');
      if (content == std::string::npos) {
        lines.emplace_back();
        StartLine(line_ + 1);
        continue;
      }
      if (int(content) <= parent) break;
      if (!indent) indent = content;
      if (content < indent) break;
      lines.push_back(s.substr(indent));
      StartLine(line_ + 1);
    }
    size_t trailing = 0;
    while (!lines.empty() && lines.back().empty()) lines.pop_back(), ++trailing;
    std::string out;
    for (size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      if (i > 0) {
        const std::string& before = lines[i - 1];
        if (!folded) {
          out += '\n';
        } else if (l.empty()) {
          out += '\n';  // folded: a blank line is one line break
          continue;
        } else if (!before.empty()) {
          out += IsSpace(l[0]) || IsSpace(before[0]) ? '\n' : ' ';
        }
      }
      out += l;
    }
    if (!lines.empty() && chomp != '-') out += '\n';
    if (chomp == '+') out += std::string(trailing, '\n');
    return out;
  }

  std::vector<std::string> lines_;
  size_t line_ = 0, col_ = 0;
};

}  // namespace

YamlNode ParseYaml(const std::string& text) { return Parser(text).Document(); }

}  // namespace lpir
