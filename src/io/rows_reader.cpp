#include "sfit/io/rows_reader.h"
#include "sfit/weights.h"

#include <sys/stat.h>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "input_file.h"
#include "parse_double.h"
#include "sfit/error.h"

namespace sfit::io {
namespace {

// Spaces, tabs, commas and the other ASCII blanks separate numbers; '#' starts a comment.
enum CharClass : unsigned char { kToken, kSeparator, kComment };
constexpr auto kClass = [] {
  std::array<CharClass, 256> t{};
  for (unsigned char c : {' ', '\t', ',', '\r', '\f', '\v'}) t[c] = kSeparator;
  t[static_cast<unsigned char>('#')] = kComment;
  return t;
}();

// Incremental parser: feed() whole lines; finish() closes the last row.
class Parser {
 public:
  explicit Parser(const std::string& name) { out_.name = name; }

  void line(std::string_view s) {
    ++line_no_;
    if (line_no_ == 1 && s.size() >= 3 && static_cast<unsigned char>(s[0]) == 0xEF &&
        static_cast<unsigned char>(s[1]) == 0xBB && static_cast<unsigned char>(s[2]) == 0xBF) {
      s.remove_prefix(3);
      col_base_ = 3;
    } else {
      col_base_ = 0;
    }
    if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
    double v[4];
    int n = 0;
    std::size_t i = 0;
    bool comment = false;
    std::size_t weight_col = 0;
    // One pass with a character-class table (this loop runs for every byte of the input).
    const std::size_t size = s.size();
    const char* data = s.data();
    while (i < size) {
      const CharClass c = kClass[static_cast<unsigned char>(data[i])];
      if (c == kSeparator) {
        ++i;
        continue;
      }
      if (c == kComment) {
        comment = true;
        break;
      }
      std::size_t e = i + 1;
      while (e < size && kClass[static_cast<unsigned char>(data[e])] == kToken) ++e;
      const std::string_view tok = s.substr(i, e - i);
      if (n == 4)
        fail(ErrorCode::kInputSyntax, i,
             "more than 4 numbers on a line: '" + detail::show_field(tok) + "'");
      if (n == 3) weight_col = i;
      v[n++] = number(tok, i);
      i = e;
    }
    if (n == 0) {
      if (!comment) blank();  // a blank line separates rows; a comment line is transparent
      return;
    }
    if (n < 3)
      fail(ErrorCode::kInputSyntax, s.size(),
           "expected 3 numbers (x y z), found " + std::to_string(n));
    weight(n, v[3], weight_col);
    if (out_.rows.open_row_size() == 0) out_.first_line.push_back(line_no_);
    out_.rows.push_point(Point(v[0], v[1], v[2]));
  }

  // [seams] An optional 4th number, the point's weight (docs/seams.md): every point has one or
  // none, and each is within kMinWeight ... kMaxWeight (rows.h).
  void weight(int n, double w, std::size_t col) {
    const bool has = n == 4;
    if (out_.rows.points().empty()) weighted_ = has;
    if (has != weighted_)
      fail(ErrorCode::kInputSyntax, col,
           has ? "a weight (4th number) here, but the first point has none: give every point "
                 "x y z or every point x y z weight"
               : "no weight (4th number) here, but the first point has one: give every point "
                 "x y z weight");
    if (!has) return;
    if (const std::string why = weight_error(w); !why.empty())
      fail(ErrorCode::kInputData, col, why);
    out_.rows.push_weight(w);
  }

  void too_long() {
    ++line_no_;
    col_base_ = 0;
    fail(ErrorCode::kInputSyntax, 0,
         "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
  }

  RowsFile finish() {
    blank();
    if (out_.rows.total_points() == 0) {
      Place p{.file = out_.name};
      throw Error(ErrorCode::kInputData, "no points: the input holds no 'x y z' line", p);
    }
    return std::move(out_);
  }

 private:
  void blank() {
    if (out_.rows.open_row_size() > 0) out_.rows.end_row();
  }

  double number(std::string_view tok, std::size_t col) {
    double x = 0;
    const detail::FieldNumber what = detail::read_field_number(tok, x);
    if (what != detail::FieldNumber::kOk) detail::throw_field_error(what, tok, place(col));
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
  bool weighted_ = false;
};

}  // namespace

RowsFile parse_rows(std::string_view text, const std::string& name) {
  Parser p(name);
  detail::feed_lines(text, kMaxLineBytes, p);
  return p.finish();
}

RowsFile read_rows(const std::string& path) {
  const std::string name = path;
  detail::InputFile f = detail::open_input(path);
  Parser p(name);
  constexpr std::size_t kBlock = 1 << 22;
  std::string buf;
  buf.reserve(kBlock + 4096);
  // Not zeroed: fread() fills what is read, and a small file touches only its own pages (a
  // zeroed block cost a 4 MB memset and its page faults on every read of a tiny file).
  const std::unique_ptr<char[]> chunk(new char[kBlock]);
  while (true) {
    const std::size_t got = std::fread(chunk.get(), 1, kBlock, f.get());
    if (got == 0) {
      if (std::ferror(f.get()))
        throw Error(ErrorCode::kInputUnreadable,
                    std::string("cannot read input: ") + std::strerror(errno), Place{.file = name});
      break;
    }
    buf.append(chunk.get(), got);
    std::size_t start = 0;
    while (true) {
      const std::size_t nl = buf.find('\n', start);
      if (nl == std::string::npos) break;
      if (nl - start > kMaxLineBytes) p.too_long();
      p.line(std::string_view(buf).substr(start, nl - start));
      start = nl + 1;
    }
    buf.erase(0, start);
    if (buf.size() > kMaxLineBytes) p.too_long();
  }
  if (!buf.empty()) p.line(buf);
  return p.finish();
}

}  // namespace sfit::io
