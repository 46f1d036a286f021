#include "sfit/io/csv_reader.h"
#include "sfit/weights.h"

#include <sys/stat.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "input_file.h"
#include "parse_double.h"
#include "sfit/error.h"

namespace sfit::io {
namespace {

struct Field {
  std::string_view text;  // trimmed
  std::size_t column;     // 0-based byte offset of the field's first character in the line
};

bool is_separator(char c) {
  return c == ',' || c == ';' || c == '\t';
}

std::vector<Field> split(std::string_view s) {
  std::vector<Field> out;
  std::size_t start = 0;
  while (true) {
    std::size_t end = start;
    while (end < s.size() && !is_separator(s[end])) ++end;
    std::size_t b = start, e = end;
    while (b < e && (s[b] == ' ' || s[b] == '\r')) ++b;
    while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\r')) --e;
    out.push_back({s.substr(b, e - b), b});
    if (end >= s.size()) break;
    start = end + 1;
  }
  return out;
}

std::string show(std::string_view tok) {
  return detail::show_field(tok);
}

std::string lower_unquoted(std::string_view t) {
  if (t.size() >= 2 && (t.front() == '"' || t.front() == '\'') && t.back() == t.front())
    t = t.substr(1, t.size() - 2);
  std::string s(t);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  while (!s.empty() && s.back() == ' ') s.pop_back();
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  return s;
}

class Parser {
 public:
  explicit Parser(const std::string& name) { out_.name = name; }

  void line(std::string_view s) {
    ++line_no_;
    col_base_ = 0;
    if (line_no_ == 1 && s.size() >= 3 && static_cast<unsigned char>(s[0]) == 0xEF &&
        static_cast<unsigned char>(s[1]) == 0xBB && static_cast<unsigned char>(s[2]) == 0xBF) {
      s.remove_prefix(3);
      col_base_ = 3;
    }
    if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
    std::size_t first = 0;
    while (first < s.size() && (s[first] == ' ' || s[first] == '\t')) ++first;
    if (first == s.size() || std::all_of(s.begin(), s.end(), [](char c) {
          return c == ' ' || c == '\t' || is_separator(c);
        })) {
      if (!by_row_column_) end_row();  // a blank line separates rows in the x,y,z layout
      return;
    }
    if (s[first] == '#') return;
    const std::vector<Field> f = split(s);
    if (!layout_known_) {
      layout_known_ = true;
      if (!all_numbers(f)) {
        header(f);
        return;
      }
      x_ = 0, y_ = 1, z_ = 2;
      columns_ = f.size() == 4 ? 4 : 3;  // [seams] x,y,z,weight
      if (columns_ == 4) {
        w_ = 3;
        layout_ = "x,y,z,weight";
      }
    }
    if (f.size() != columns_)
      fail(ErrorCode::kInputSyntax, f.size() > columns_ ? f[columns_].column : s.size(),
           "expected " + std::to_string(columns_) + " fields (" + layout_ + "), found " +
               std::to_string(f.size()));
    if (by_row_column_) {
      const std::string id(f[row_].text);
      if (id.empty()) fail(ErrorCode::kInputSyntax, f[row_].column, "empty row value");
      if (!has_row_ || id != current_row_) {
        if (has_row_) end_row();
        const auto seen = ended_.find(id);
        if (seen != ended_.end())
          fail(ErrorCode::kInputSyntax, f[row_].column,
               "row '" + show(id) + "' already ended at line " + std::to_string(seen->second) +
                   "; the points of a row must be consecutive lines");
        current_row_ = id;
        has_row_ = true;
      }
    }
    const Point p(number(f[x_]), number(f[y_]), number(f[z_]));
    if (w_ != kNone) {  // [seams] the point's weight (docs/seams.md)
      const double w = number(f[w_]);
      if (const std::string why = weight_error(w); !why.empty())
        fail(ErrorCode::kInputData, f[w_].column, why);
      out_.rows.push_weight(w);
    }
    if (out_.rows.open_row_size() == 0) out_.first_line.push_back(line_no_);
    out_.rows.push_point(p);
    last_point_line_ = line_no_;
  }

  void too_long() {
    ++line_no_;
    col_base_ = 0;
    fail(ErrorCode::kInputSyntax, 0,
         "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
  }

  RowsFile finish() {
    end_row();
    if (out_.rows.total_points() == 0)
      throw Error(ErrorCode::kInputData, "no points: the CSV holds no x,y,z line",
                  Place{.file = out_.name});
    return std::move(out_);
  }

 private:
  static bool is_number(std::string_view t) {
    const char* b = t.data();
    const char* e = b + t.size();
    if (b != e && (*b == '+' || *b == '-')) ++b;
    if (b == e) return false;
    // A field starting like a number counts as one (its errors are reported as numbers).
    return std::isdigit(static_cast<unsigned char>(*b)) || *b == '.' ||
           lower_unquoted(std::string_view(b, e - b)).starts_with("nan") ||
           lower_unquoted(std::string_view(b, e - b)).starts_with("inf");
  }
  static bool all_numbers(const std::vector<Field>& f) {
    return std::all_of(f.begin(), f.end(), [](const Field& x) { return is_number(x.text); });
  }

  void header(const std::vector<Field>& f) {
    std::map<std::string, std::size_t> at;
    for (std::size_t k = 0; k < f.size(); ++k) {
      const std::string n = lower_unquoted(f[k].text);
      if (at.count(n) && (n == "x" || n == "y" || n == "z" || n == "row"))
        fail(ErrorCode::kInputSyntax, f[k].column,
             "column '" + show(n) + "' named twice in the header");
      at.emplace(n, k);
    }
    for (const char* need : {"x", "y", "z"})
      if (!at.count(need))
        fail(ErrorCode::kInputSyntax, f[0].column,
             std::string("the header names no '") + need +
                 "' column (expected row,x,y,z or x,y,z; found '" +
                 show(std::string(f.front().text.data(),
                                  f.back().text.data() + f.back().text.size())) +
                 "')");
    x_ = at["x"], y_ = at["y"], z_ = at["z"];
    if (at.count("weight")) w_ = at["weight"];
    if (at.count("w")) w_ = at["w"];
    columns_ = f.size();
    if (at.count("row")) {
      by_row_column_ = true;
      row_ = at["row"];
    }
    layout_.clear();
    for (std::size_t k = 0; k < f.size(); ++k)
      layout_ += (k ? "," : "") + lower_unquoted(f[k].text);
  }

  void end_row() {
    if (out_.rows.open_row_size() == 0) return;
    out_.rows.end_row();
    if (by_row_column_ && has_row_) ended_.emplace(current_row_, last_point_line_);
  }

  double number(const Field& f) {
    double x = 0;
    const detail::FieldNumber what = detail::read_field_number(f.text, x);
    if (what != detail::FieldNumber::kOk) detail::throw_field_error(what, f.text, place(f.column));
    return x;
  }

  [[noreturn]] void fail(ErrorCode code, std::size_t col0, const std::string& msg) {
    throw Error(code, msg, place(col0));
  }

  Place place(std::size_t col0) const {
    return detail::reading_place(out_.name, line_no_, col0 + col_base_ + 1, out_.rows);
  }

  RowsFile out_;
  long line_no_ = 0;
  std::size_t col_base_ = 0;
  bool layout_known_ = false;
  bool by_row_column_ = false;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t x_ = 0, y_ = 1, z_ = 2, row_ = 0, columns_ = 3, w_ = kNone;
  std::string layout_ = "x,y,z";
  bool has_row_ = false;
  std::string current_row_;
  long last_point_line_ = 0;
  std::map<std::string, long> ended_;  // row value -> line of its last point
};

}  // namespace

RowsFile parse_csv(std::string_view text, const std::string& name) {
  Parser p(name);
  detail::feed_lines(text, kMaxLineBytes, p);
  return p.finish();
}

RowsFile read_csv(const std::string& path) {
  std::string text;
  if (path == "-") {
    std::ostringstream ss;
    ss << std::cin.rdbuf();
    text = ss.str();
  } else {
    detail::InputFile f = detail::open_input(path);
    char block[1 << 16];
    std::size_t got;
    while ((got = std::fread(block, 1, sizeof block, f.get())) > 0) text.append(block, got);
    if (std::ferror(f.get()))
      throw Error(ErrorCode::kInputUnreadable, "cannot read input", Place{.file = path});
  }
  return parse_csv(text, path);
}

}  // namespace sfit::io
