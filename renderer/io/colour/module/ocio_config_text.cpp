// The pass tokenizes YAML as yaml-cpp 0.7 does (its scanner decides where every scalar, comment
// and tag ends, so this one must end them at the same bytes: a scalar read longer than yaml-cpp
// reads it would hide entries) and keeps a stack of open collections: block collections by their
// indentation, as yaml-cpp keeps its indents, flow collections by their brackets. It builds no
// nodes: its cost is one look at each byte and one frame per open collection. Where a document is
// not valid YAML the count may be anything (OpenColorIO refuses it); where it is valid, the count
// errs high only.
#include "io/colour/module/ocio_config_text.h"

#include <algorithm>
#include <vector>

namespace kiln::colour_module {
namespace {

// Keys whose sequences OpenColorIO reads as one vector of numbers (a matrix, a CDL slope, a
// curve's control points): a config holds hundreds of them, and their items are not entries.
bool numeric_key(const std::string& key) {
  static const char* const keys[] = {"matrix",
                                     "offset",
                                     "slope",
                                     "power",
                                     "value",
                                     "gamma",
                                     "params",
                                     "allocationvars",
                                     "vars",
                                     "luma",
                                     "rgb",
                                     "control_points",
                                     "slopes",
                                     "base",
                                     "lin_side_offset",
                                     "lin_side_slope",
                                     "log_side_offset",
                                     "log_side_slope",
                                     "lin_side_break",
                                     "linear_slope"};
  for (const char* k : keys)
    if (key == k) return true;
  return false;
}

bool digit(char c) { return c >= '0' && c <= '9'; }
bool hex(char c) { return digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }
bool word(char c) { return digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '-'; }
bool blank(char c) { return c == ' ' || c == '\t'; }

// A number as yaml-cpp converts one: decimal with optional fraction and exponent, .inf, .nan.
bool is_number(const std::string& s) {
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::string rest = s.substr(i);
  for (const char* special : {".inf", ".Inf", ".INF", ".nan", ".NaN", ".NAN"})
    if (rest == special) return true;
  size_t digits = 0;
  for (; i < s.size() && digit(s[i]); ++i) ++digits;
  if (i < s.size() && s[i] == '.')
    for (++i; i < s.size() && digit(s[i]); ++i) ++digits;
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exponent = 0;
    for (; i < s.size() && digit(s[i]); ++i) ++exponent;
    if (exponent == 0) return false;
  }
  return i == s.size();
}

enum class collection { block_map, block_seq, flow_map, flow_seq };

// An open collection.
struct frame {
  collection kind = collection::block_map;
  long indent = -1;          // block collections: the column of their keys or dashes
  uint64_t items = 0;        // pairs or items so far
  bool item_open = false;    // flow collections: an item begun since the last comma
  bool numbers_only = true;  // sequences: every item so far one plain number
  std::string key;           // the key this collection is the value of ("" for none)
};

class scanner {
 public:
  explicit scanner(std::string_view text) : s_(text) {}

  config_text_shape run() {
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") i_ = line_start_ = 3;  // a UTF-8 byte order mark
    while (!done_ && i_ < s_.size())
      if (start_line()) rest_of_line();
    while (!stack_.empty()) {  // collections open at the end (yaml-cpp refuses unclosed flows)
      if (stack_.back().item_open) ++stack_.back().items;
      pop();
    }
    return shape_;
  }

 private:
  // yaml-cpp's line breaks are LF and CR LF; a lone CR is text.
  bool at_break(size_t j) const {
    return j < s_.size() && (s_[j] == '\n' || (s_[j] == '\r' && j + 1 < s_.size() && s_[j + 1] == '\n'));
  }
  bool blank_break_or_end(size_t j) const { return j >= s_.size() || blank(s_[j]) || at_break(j); }

  void eat_break() {
    i_ += s_[i_] == '\r' ? 2 : 1;
    ++line_;
    line_start_ = i_;
  }

  void skip_to_break() {
    while (i_ < s_.size() && !at_break(i_)) ++i_;
  }

  long column() const { return long(i_ - line_start_); }

  // A document marker (--- or ...) at the start of the line at j.
  bool document_marker(size_t j) const {
    return j == line_start_ && (s_.compare(j, 3, "---") == 0 || s_.compare(j, 3, "...") == 0) &&
           blank_break_or_end(j + 3);
  }

  void refuse(const std::string& what) {
    shape_.refusal = "line " + std::to_string(line_) + " has " + what;
    done_ = true;
  }

  // The indentation of the innermost block collection, -1 at the top (yaml-cpp's top indent).
  long top_indent() const {
    for (auto f = stack_.rbegin(); f != stack_.rend(); ++f)
      if (f->kind == collection::block_map || f->kind == collection::block_seq) return f->indent;
    return -1;
  }

  // The frame at the top ends: a sequence's items count now, when it is known whether they
  // were all numbers; a flow mapping's pairs too (a block mapping's count as they come).
  void pop() {
    const frame& f = stack_.back();
    if (f.kind == collection::block_seq || f.kind == collection::flow_seq) {
      if (!(f.numbers_only && numeric_key(f.key))) shape_.entries += f.items;
    } else if (f.kind == collection::flow_map && stack_.size() <= 2) {
      shape_.entries += f.items;
    }
    stack_.pop_back();
  }

  void push(collection kind, long indent, const std::string& key) {
    frame f;
    f.kind = kind;
    f.indent = indent;
    f.key = key;
    stack_.push_back(std::move(f));
  }

  // The first node of a block sequence's newest entry decides whether the entry is a number.
  void entry_content(bool plain_number) {
    if (entry_frame_ < stack_.size() && !plain_number) stack_[entry_frame_].numbers_only = false;
    entry_frame_ = size_t(-1);
  }

  // Indentation, blank and comment lines, document markers and directives; closes the block
  // collections the line's indentation ends. False when nothing is left of the line to read.
  bool start_line() {
    entry_content(false);  // an entry whose content, if any, is on later lines
    long indent = 0;
    while (i_ < s_.size() && s_[i_] == ' ') {
      ++i_;
      ++indent;
    }
    if (i_ >= s_.size()) return false;
    if (at_break(i_)) {
      eat_break();
      return false;
    }
    const char c = s_[i_];
    if (c == '#') {
      skip_to_break();
      return false;
    }
    if (c == '\t') {
      while (i_ < s_.size() && blank(s_[i_])) ++i_;
      if (i_ >= s_.size() || at_break(i_) || s_[i_] == '#') return false;
      refuse("a tab in its indentation (YAML indents with spaces)");
      return false;
    }
    if (document_marker(i_)) {
      if (seen_content_ || c == '.') {
        done_ = seen_content_;  // yaml-cpp reads the first document only
        skip_to_break();
        return false;
      }
      seen_content_ = true;
      i_ += 3;
      return true;
    }
    if (indent == 0 && c == '%') {
      if (s_.compare(i_, 4, "%TAG") == 0) refuse("a %TAG directive");
      skip_to_break();
      return false;
    }
    seen_content_ = true;
    const bool entry = c == '-' && blank_break_or_end(i_ + 1);
    while (!stack_.empty()) {
      const frame& f = stack_.back();
      if (f.indent > indent || (f.indent == indent && f.kind == collection::block_seq && !entry))
        pop();
      else
        break;
    }
    return true;
  }

  void rest_of_line() {
    while (!done_ && i_ < s_.size()) {
      const char c = s_[i_];
      if (blank(c)) {
        ++i_;
        continue;
      }
      if (at_break(i_)) {
        eat_break();
        return;
      }
      const long col = column();
      if (c == '#') {
        skip_to_break();
      } else if (c == '-' && blank_break_or_end(i_ + 1)) {
        entry_content(false);
        block_entry(col);
        ++i_;
      } else if (c == '?' && i_ + 1 < s_.size() && (blank(s_[i_ + 1]) || at_break(i_ + 1))) {
        refuse("an explicit key (?)");
      } else if (c == ':' && blank_break_or_end(i_ + 1)) {
        entry_content(false);
        block_key(col, "");
        ++i_;
      } else if (c == '&' || c == '*') {
        refuse(c == '&' ? "a YAML anchor (&)" : "a YAML alias (*)");
      } else if (c == '!') {
        entry_content(false);
        tag();
      } else if (c == '|' || c == '>') {
        entry_content(false);
        block_scalar();
        return;
      } else if (c == '[' || c == '{') {
        entry_content(false);
        flow();
        after_node(col, "", false);
      } else if (c == '"' || c == '\'') {
        const std::string text = quoted();
        after_node(col, text, false);
      } else if (c == ']' || c == '}' || c == ',' || c == '%' || c == '@' || c == '`') {
        ++i_;  // a token yaml-cpp refuses here
      } else {
        bool one_line = true;
        const std::string text = plain_block(one_line);
        after_node(col, text, one_line && is_number(text));
      }
    }
  }

  // A node at col just ended: a key when a ':' follows, else a value.
  void after_node(long col, const std::string& text, bool plain_number) {
    size_t j = i_;
    while (j < s_.size() && blank(s_[j])) ++j;
    if (j < s_.size() && s_[j] == ':' && blank_break_or_end(j + 1)) {
      entry_content(false);
      i_ = j + 1;
      block_key(col, text);
      return;
    }
    entry_content(plain_number);
    pending_key_.clear();
  }

  void block_entry(long col) {
    if (!stack_.empty() && stack_.back().kind == collection::block_seq && stack_.back().indent == col) {
      ++stack_.back().items;
    } else {
      push(collection::block_seq, col, pending_key_);
      stack_.back().items = 1;
    }
    entry_frame_ = stack_.size() - 1;
    pending_key_.clear();
  }

  void block_key(long col, const std::string& text) {
    if (!stack_.empty() && stack_.back().kind == collection::block_map && stack_.back().indent == col) {
      ++stack_.back().items;
    } else {
      push(collection::block_map, col, pending_key_);
      stack_.back().items = 1;
    }
    if (stack_.size() <= 2) ++shape_.entries;
    pending_key_ = text;
  }

  // A tag: !<verbatim> to its '>', or handle and suffix over yaml-cpp's tag characters.
  void tag() {
    const size_t start = i_++;
    if (i_ < s_.size() && s_[i_] == '<') {
      while (i_ < s_.size() && s_[i_] != '>' && !blank_break_or_end(i_)) ++i_;
      if (i_ < s_.size() && s_[i_] == '>') ++i_;
    } else {
      static const std::string_view others = "#;/?:@&=+$_.~*'()!";
      while (i_ < s_.size()) {
        const char c = s_[i_];
        if (word(c) || others.find(c) != std::string_view::npos)
          ++i_;
        else if (c == '%' && i_ + 2 < s_.size() && hex(s_[i_ + 1]) && hex(s_[i_ + 2]))
          i_ += 3;
        else
          break;
      }
    }
    if (s_.compare(start, i_ - start, "!<ColorSpace>") == 0) ++shape_.colour_spaces;
  }

  // A literal (|) or folded (>) scalar: its header line, then its lines, as yaml-cpp's
  // ScanBlockScalar finds them (indentation given, or set by the first lines).
  void block_scalar() {
    long indent = 1;
    bool detect = true;
    for (++i_; i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-' || digit(s_[i_])); ++i_)
      if (digit(s_[i_])) {
        indent = s_[i_] - '0';
        detect = false;
      }
    skip_to_break();  // blanks and a comment; anything else there is an error to yaml-cpp
    if (top_indent() >= 0) indent += top_indent();
    bool found = false;  // a line with text seen
    while (i_ < s_.size()) {
      eat_break();
      size_t j = i_;
      long col = 0;
      while (j < s_.size() && s_[j] == ' ' && (col < indent || (detect && !found))) {
        ++j;
        ++col;
      }
      if (detect && !found) indent = std::max(indent, col);
      if (j >= s_.size()) {
        i_ = j;
        return;
      }
      const bool empty = at_break(j);
      if ((!empty && col < indent) || (s_[j] == '\t' && col < indent)) return;  // the scalar ended
      found = found || !empty;
      i_ = j;
      skip_to_break();
    }
  }

  // A single- or double-quoted scalar, over as many lines as it takes; its text unescaped only
  // as far as '' (enough to compare keys: an escaped key matches no numeric key).
  std::string quoted() {
    const char quote = s_[i_++];
    std::string text;
    while (i_ < s_.size()) {
      if (at_break(i_)) {
        eat_break();
        text += ' ';
        continue;
      }
      const char c = s_[i_];
      if (c == quote) {
        if (quote == '\'' && i_ + 1 < s_.size() && s_[i_ + 1] == '\'') {
          text += '\'';
          i_ += 2;
          continue;
        }
        ++i_;
        return text;
      }
      if (quote == '"' && c == '\\' && i_ + 1 < s_.size()) {
        ++i_;
        if (at_break(i_)) {
          eat_break();
          continue;
        }
        text += c;
        text += s_[i_++];
        continue;
      }
      text += c;
      ++i_;
    }
    return text;
  }

  // Up to the end of a plain scalar's line: a ": " (a key follows), a " #" (a comment) or the break.
  std::string plain_line() {
    const size_t start = i_;
    while (i_ < s_.size() && !at_break(i_)) {
      const char c = s_[i_];
      if (c == ':' && blank_break_or_end(i_ + 1)) break;
      if (c == '#' && i_ > start && blank(s_[i_ - 1])) break;
      ++i_;
    }
    size_t end = i_;
    while (end > start && blank(s_[end - 1])) --end;
    return std::string(s_.substr(start, end - start));
  }

  // A plain scalar in a block: its first line and, when that ends at a break, the lines yaml-cpp
  // continues it on (indented past the innermost block collection) up to a ": " or " #".
  std::string plain_block(bool& one_line) {
    const std::string text = plain_line();
    const long needed = top_indent() + 1;
    while (i_ < s_.size() && at_break(i_)) {
      const size_t here = i_;
      const uint64_t line = line_;
      const size_t start = line_start_;
      eat_break();
      size_t j = i_;
      while (j < s_.size() && blank(s_[j])) ++j;
      if (j >= s_.size()) {
        i_ = j;
        break;
      }
      if (at_break(j)) {  // an empty line: the scalar may go on after it
        i_ = j;
        continue;
      }
      if (long(j - i_) < needed || document_marker(i_) || s_[j] == '#') {
        // Not part of the scalar: left to be read as a line of its own.
        if (long(j - i_) < needed || document_marker(i_)) {
          i_ = here;
          line_ = line;
          line_start_ = start;
        } else {
          i_ = j;
        }
        break;
      }
      one_line = false;
      i_ = j;
      plain_line();
    }
    return text;
  }

  // A plain scalar in a flow collection, to yaml-cpp's end: a ": " (or ':' before , ] }), any of
  // , ? [ ] { }, a " #" or the break. Its following lines are read as scalars of their own.
  std::string plain_flow() {
    const size_t start = i_;
    while (i_ < s_.size() && !at_break(i_)) {
      const char c = s_[i_];
      if (c == ':' &&
          (blank_break_or_end(i_ + 1) || s_[i_ + 1] == ',' || s_[i_ + 1] == ']' || s_[i_ + 1] == '}'))
        break;
      if (c == ',' || c == '?' || c == '[' || c == ']' || c == '{' || c == '}') break;
      if (c == '#' && i_ > start && blank(s_[i_ - 1])) break;
      ++i_;
    }
    size_t end = i_;
    while (end > start && blank(s_[end - 1])) --end;
    return std::string(s_.substr(start, end - start));
  }

  // A flow collection from its opening bracket to the matching close, over any number of lines.
  void flow() {
    const size_t outer = stack_.size() + 1;
    push(s_[i_] == '[' ? collection::flow_seq : collection::flow_map, -1, pending_key_);
    pending_key_.clear();
    ++i_;
    std::string key, last;  // the key of the next nested collection; the last scalar read
    bool json = false;      // after a quoted scalar or a closing bracket, any ':' is a value
    while (!done_ && i_ < s_.size() && stack_.size() >= outer) {
      const char c = s_[i_];
      if (blank(c)) {
        ++i_;
        continue;
      }
      if (at_break(i_)) {
        eat_break();
        continue;
      }
      frame& top = stack_.back();
      const bool was_json = json;
      json = false;
      if (c == '#') {
        skip_to_break();  // at a token's start, always a comment to yaml-cpp
      } else if (c == '[' || c == '{') {
        top.item_open = true;
        top.numbers_only = false;
        push(c == '[' ? collection::flow_seq : collection::flow_map, -1, key);
        key.clear();
        ++i_;
      } else if (c == ']' || c == '}') {
        if (top.item_open) ++top.items;
        pop();
        key.clear();
        json = true;
        ++i_;
      } else if (c == ',') {
        if (top.item_open) ++top.items;
        top.item_open = false;
        key.clear();
        ++i_;
      } else if (c == '?' && blank_break_or_end(i_ + 1)) {
        refuse("an explicit key (?)");
      } else if (c == '&' || c == '*') {
        refuse(c == '&' ? "a YAML anchor (&)" : "a YAML alias (*)");
      } else if (c == '!') {
        tag();
      } else if (c == ':' && (was_json || blank_break_or_end(i_ + 1) || s_[i_ + 1] == ',' ||
                              s_[i_ + 1] == ']' || s_[i_ + 1] == '}')) {
        top.item_open = true;
        top.numbers_only = false;
        key = last;
        ++i_;
      } else if (c == '"' || c == '\'') {
        last = quoted();
        top.item_open = true;
        top.numbers_only = false;
        json = true;
      } else if (c == '?' || c == '|' || c == '>' || c == '%' || c == '@' || c == '`') {
        ++i_;  // a token yaml-cpp refuses here
      } else {
        const size_t before = i_;
        last = plain_flow();
        if (i_ == before) ++i_;  // never loop in place
        top.item_open = true;
        if (!is_number(last)) top.numbers_only = false;
      }
    }
  }

  std::string_view s_;
  size_t i_ = 0;
  size_t line_start_ = 0;
  uint64_t line_ = 1;
  bool done_ = false;
  bool seen_content_ = false;
  std::vector<frame> stack_;
  std::string pending_key_;          // a block key whose value has not begun
  size_t entry_frame_ = size_t(-1);  // the block sequence whose newest entry has no content yet
  config_text_shape shape_;
};

}  // namespace

config_text_shape scan_config_text(std::string_view text) { return scanner(text).run(); }

}  // namespace kiln::colour_module
