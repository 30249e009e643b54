#include "bodies/step_placement_lists.h"

#include <climits>
#include <cstddef>
#include <unordered_set>

namespace contactcore {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// The quote closing the string opened at `open`, where OCCT 7.6's lexer
// (step.lex) closes it: a quote followed by blanks (spaces, line ends) and
// then ',' or ')'; any other quote is part of the string ('' included).
// npos when the string runs on past `end`.
std::size_t string_close(std::string_view text, std::size_t open, std::size_t end) {
  for (std::size_t i = open + 1; i < end; ++i) {
    if (text[i] != '\'') continue;
    std::size_t next = i + 1;
    while (next < end && (text[next] == ' ' || text[next] == '\n' || text[next] == '\r')) ++next;
    if (next < end && (text[next] == ',' || text[next] == ')')) return i;
  }
  return std::string_view::npos;
}

// Reads one record's text, skipping blanks and comments between tokens;
// every step fails (returns false) on anything it does not expect.
class Cursor {
 public:
  Cursor(std::string_view text, std::size_t from, std::size_t end) : text_(text), at_(from), end_(end) {}

  std::size_t at() const { return at_; }
  bool done() {
    skip();
    return at_ == end_;
  }
  bool take(char c) {
    skip();
    if (at_ < end_ && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }
  bool peek(char c) {
    skip();
    return at_ < end_ && text_[at_] == c;
  }
  // #123 -> 123 (false beyond INT_MAX: such a record is left alone).
  bool reference(int& number) {
    if (!take('#')) return false;
    long long value = 0;
    const std::size_t start = at_;
    while (at_ < end_ && text_[at_] >= '0' && text_[at_] <= '9') {
      value = value * 10 + (text_[at_] - '0');
      if (value > INT_MAX) return false;
      ++at_;
    }
    if (at_ == start) return false;
    number = static_cast<int>(value);
    return true;
  }
  bool keyword(std::string_view& word) {
    skip();
    const std::size_t start = at_;
    while (at_ < end_ && ((text_[at_] >= 'A' && text_[at_] <= 'Z') || (text_[at_] >= '0' && text_[at_] <= '9') ||
                          text_[at_] == '_'))
      ++at_;
    word = text_.substr(start, at_ - start);
    return at_ > start;
  }
  bool string() {
    if (!peek('\'')) return false;
    const std::size_t close = string_close(text_, at_, end_);
    if (close == std::string_view::npos) return false;
    at_ = close + 1;
    return true;
  }

 private:
  void skip() {
    while (at_ < end_) {
      if (is_space(text_[at_])) {
        ++at_;
      } else if (text_[at_] == '/' && at_ + 1 < end_ && text_[at_ + 1] == '*') {
        const std::size_t close = text_.find("*/", at_ + 2);
        at_ = close == std::string_view::npos || close + 2 > end_ ? end_ : close + 2;
      } else {
        return;
      }
    }
  }
  std::string_view text_;
  std::size_t at_, end_;
};

struct Record {
  int number = 0;
  std::size_t arguments = 0, end = 0;  // the '(' opening its arguments, the ';' closing it
};

struct ListToShorten {
  std::size_t open = 0, close = 0;  // the list's '(' and ')'
  int representation = 0;
  std::vector<int> items;
};

// SHAPE_REPRESENTATION('name',(#a,#b,...),#context): the list's bounds and items.
bool read_shape_representation(std::string_view text, const Record& record, ListToShorten& list) {
  Cursor cursor(text, record.arguments, record.end);
  if (!cursor.take('(') || !cursor.string() || !cursor.take(',') || !cursor.peek('(')) return false;
  list.open = cursor.at();
  cursor.take('(');
  for (;;) {
    int item = 0;
    if (!cursor.reference(item)) return false;
    list.items.push_back(item);
    if (cursor.take(',')) continue;
    if (!cursor.peek(')')) return false;
    list.close = cursor.at();
    cursor.take(')');
    break;
  }
  int context = 0;
  if (!cursor.take(',') || !cursor.reference(context) || !cursor.take(')') || !cursor.done()) return false;
  list.representation = record.number;
  return true;
}

}  // namespace

ShortenedPlacementLists shorten_placement_lists(std::string_view text) {
  ShortenedPlacementLists out;
  std::unordered_set<int> placements;  // the AXIS2_PLACEMENT_3Ds
  std::vector<Record> representations;  // the SHAPE_REPRESENTATIONs (simple records)
  // Records end at ';' outside strings and comments.
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\'') {
      const std::size_t close = string_close(text, i, text.size());
      if (close == std::string_view::npos) break;  // the rest is one string
      i = close;
    } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const std::size_t close = text.find("*/", i + 2);
      if (close == std::string_view::npos) break;
      i = close + 1;
    } else if (c == ';') {
      Cursor cursor(text, start, i);
      Record record;
      std::string_view type;
      if (cursor.reference(record.number) && cursor.take('=') && cursor.keyword(type) && cursor.peek('(')) {
        record.arguments = cursor.at();
        record.end = i;
        if (type == "AXIS2_PLACEMENT_3D") placements.insert(record.number);
        else if (type == "SHAPE_REPRESENTATION") representations.push_back(record);
      }
      start = i + 1;
    }
  }
  std::vector<ListToShorten> lists;
  for (const Record& record : representations) {
    ListToShorten list;
    if (!read_shape_representation(text, record, list) || list.items.size() < 2) continue;
    bool all_placements = true;
    for (int item : list.items) all_placements = all_placements && placements.count(item) > 0;
    if (all_placements) lists.push_back(std::move(list));
  }
  if (lists.empty()) return out;
  out.text.reserve(text.size());
  std::size_t copied = 0;
  for (ListToShorten& list : lists) {
    out.text.append(text.substr(copied, list.open - copied));
    out.text += "(#" + std::to_string(list.items.front()) + ")";
    copied = list.close + 1;
    list.items.erase(list.items.begin());
    out.removed[list.representation] = std::move(list.items);
  }
  out.text.append(text.substr(copied));
  return out;
}

}  // namespace contactcore
