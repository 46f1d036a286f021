// The bad-input corpus: every case of tests/bad_input/cases.tsv runs the sfit CLI
// and must give its exit code and its one exact error line, and must leave no output file,
// no temporary file, and any existing output untouched. Accepted cases (exit 0) must write a
// surface that reads back with finite control points.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sfit/io/surface_json.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace sfit::test {
namespace {

const std::string kCorpus = std::string(SFIT_TESTS_DIR) + "/bad_input";
const std::string kOld = "an existing output that must survive\n";

struct Case {
  int line = 0;
  std::string name, input, args, expect;
  int exit_code = 0;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

std::vector<std::string> split_tabs(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t tab = s.find('\t', start);
    out.push_back(s.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
    if (tab == std::string::npos) return out;
    start = tab + 1;
  }
}

std::vector<Case> load_cases() {
  std::ifstream in(kCorpus + "/cases.tsv");
  std::vector<Case> cases;
  std::string line;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    if (line.empty() || line[0] == '#') continue;
    const auto f = split_tabs(line);
    if (f.size() != 5) {
      ADD_FAILURE() << "cases.tsv:" << no << ": expected 5 tab-separated fields, got " << f.size();
      continue;
    }
    cases.push_back(Case{no, f[0], f[1], f[2], f[4], std::stoi(f[3])});
  }
  return cases;
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l)) out.push_back(l);
  return out;
}

// Every regular file under `dir` with its size, to see what a run left behind.
std::map<std::string, std::uintmax_t> files_under(const std::string& dir) {
  std::map<std::string, std::uintmax_t> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[e.path().string()] = e.file_size();
  return out;
}

// Paths given to -o/--output/--report in `args` (already expanded; no spaces in them).
std::vector<std::string> output_paths(const std::string& args) {
  std::istringstream in(args);
  std::vector<std::string> words, out;
  for (std::string w; in >> w;) words.push_back(w);
  for (std::size_t i = 0; i + 1 < words.size(); ++i)
    if (words[i] == "-o" || words[i] == "--output" || words[i] == "--report") {
      std::string p = words[i + 1];
      if (p.size() >= 2 && p.front() == '\'' && p.back() == '\'') p = p.substr(1, p.size() - 2);
      out.push_back(p);
    }
  return out;
}

// Runs a shell command line; returns the exit code (128 + signal when killed).
int shell(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Permission cases cannot fail for root, so as root they run the CLI as user nobody.
std::string unprivileged_prefix() {
  if (::geteuid() != 0) return "";
  const std::string p = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  const std::string probe = p + "'" + SFIT_CLI + "' --version >/dev/null 2>&1";
  return shell(probe) == 0 ? p : "?";
}

struct Prepared {
  std::string dir, input, args, expect, stdin_path, prefix;
};

// Builds the scratch folder of one run and expands the placeholders of `c`:
// {in} the input, {tmp} the scratch folder, {out} = {tmp}/out.json, {ro} a folder that is
// not writable, {file} a regular file (for "not a folder"), {folder} a folder "folder.json".
Prepared prepare(const Case& c, const std::string& dir, bool with_old_outputs) {
  Prepared p;
  p.dir = dir;
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file(dir + "/file", "a plain file\n");
  bool needs_unprivileged = c.args.find("{ro}") != std::string::npos;
  std::string input = c.input;
  bool from_stdin = false;
  if (!input.empty() && input[0] == '<') {
    from_stdin = true;
    input = input.substr(1);
  }
  std::string in;
  if (input == "-") {
    in = "";
  } else if (input == "@missing") {
    in = dir + "/missing.rows";
  } else if (input == "@dir") {
    in = dir + "/folder.rows";
    fs::create_directories(in);
  } else if (input == "@not_a_dir") {
    in = dir + "/file/points.rows";
  } else if (input == "@unreadable") {
    in = dir + "/unreadable.rows";
    fs::copy_file(kCorpus + "/good.rows", in);
    fs::permissions(in, fs::perms::none);
    needs_unprivileged = true;
  } else if (input == "@huge_line") {
    // A 100 MiB line between two good ones: generated here, never committed.
    in = dir + "/huge_line.rows";
    std::ofstream f(in, std::ios::binary);
    f << "0 0 0\n";
    const std::string block(1 << 20, '7');
    for (int i = 0; i < 100; ++i) f << block;
    f << "\n1 1 1\n";
  } else {
    in = kCorpus + "/" + input;
  }
  if (from_stdin) {
    p.stdin_path = in;
    in = "-";
  }
  const std::string ro = dir + "/ro";
  fs::create_directories(ro);
  // {sticky}: a sticky folder like /tmp holding taken.json, a file of the test's user, which
  // user nobody may not replace (so the case needs root, as {ro} does).
  const std::string sticky = dir + "/sticky";
  if (c.args.find("{sticky}") != std::string::npos) {
    fs::create_directories(sticky);
    fs::permissions(sticky, fs::perms::all | fs::perms::sticky_bit);
    write_file(sticky + "/taken.json", kOld);
    needs_unprivileged = true;
  }
  fs::create_directories(dir + "/folder.json");
  auto expand = [&](std::string s) {
    replace_all(s, "{in}", in);
    replace_all(s, "{out}", dir + "/out.json");
    replace_all(s, "{ro}", ro);
    replace_all(s, "{file}", dir + "/file");
    replace_all(s, "{folder}", dir + "/folder.json");
    replace_all(s, "{sticky}", sticky);
    replace_all(s, "{tmp}", dir);
    return s;
  };
  p.input = in;
  p.args = expand(c.args);
  p.expect = expand(c.expect);
  if (with_old_outputs)
    for (const auto& out : output_paths(p.args)) {
      std::error_code ec;
      if (fs::is_directory(fs::path(out).parent_path(), ec) && !fs::exists(out, ec))
        write_file(out, kOld);
    }
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                          fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  if (needs_unprivileged) {
    p.prefix = unprivileged_prefix();
    if (::geteuid() != 0 && c.args.find("{sticky}") != std::string::npos) p.prefix = "?";
    fs::permissions(dir, fs::perms::all);  // nobody may write the scratch folder itself
  }
  return p;
}

class BadInput : public ::testing::TestWithParam<Case> {};

TEST_P(BadInput, GivesItsExitCodeAndLineAndLosesNothing) {
  const Case& c = GetParam();
  SCOPED_TRACE("tests/bad_input/cases.tsv:" + std::to_string(c.line) + " (" + c.name + ")");
  const std::string base = temp_dir();
  // Error cases run twice: without and with an existing output file at every output path.
  const int runs = c.exit_code == 0 ? 1 : 2;
  for (int run = 0; run < runs; ++run) {
    SCOPED_TRACE(run == 0 ? "no existing output" : "existing output present");
    const Prepared p = prepare(c, base + "/run" + std::to_string(run), run == 1);
    if (p.prefix == "?")
      GTEST_SKIP() << "needs root able to drop to user nobody (a {sticky} case: root itself)";
    const auto before = files_under(p.dir);
    const std::string out = p.dir + "/../stdout" + std::to_string(run);
    const std::string err = p.dir + "/../stderr" + std::to_string(run);
    const std::string cmd = p.prefix + "'" + SFIT_CLI + "' " + p.args + " <'" +
                            (p.stdin_path.empty() ? std::string("/dev/null") : p.stdin_path) +
                            "' >'" + out + "' 2>'" + err + "'";
    const int code = shell(cmd);
    const std::string stderr_text = read_file(err);
    EXPECT_EQ(code, c.exit_code) << cmd << "\n" << stderr_text;
    const auto lines = lines_of(stderr_text);
    std::vector<std::string> errors;
    for (const auto& l : lines)
      if (l.rfind("sfit: error: ", 0) == 0) errors.push_back(l.substr(13));
    // A trailing '~' in the expectation means "starts with".
    const bool prefix_only = !p.expect.empty() && p.expect.back() == '~';
    const std::string want = prefix_only ? p.expect.substr(0, p.expect.size() - 1) : p.expect;
    auto matches = [&](const std::string& line) {
      return prefix_only ? line.rfind(want, 0) == 0 : line == want;
    };
    if (c.exit_code != 0) {
      ASSERT_EQ(errors.size(), 1u) << stderr_text;
      EXPECT_TRUE(matches(errors[0])) << "got:      " << errors[0] << "\nexpected: " << p.expect;
      EXPECT_EQ(lines.back(), "sfit: error: " + errors[0]) << "the error is the last line";
      // Nothing written, nothing left behind, an existing output untouched.
      EXPECT_EQ(files_under(p.dir), before);
      for (const auto& o : output_paths(p.args)) {
        if (run == 1 && before.count(o)) {
          EXPECT_EQ(read_file(o), kOld) << o;
        }
      }
    } else {
      EXPECT_TRUE(errors.empty()) << stderr_text;
      bool found = false;
      for (const auto& l : lines) found = found || matches(l);
      EXPECT_TRUE(found) << "no stderr line is: " << p.expect << "\n" << stderr_text;
      for (const auto& o : output_paths(p.args)) {
        ASSERT_TRUE(fs::exists(o)) << o;
        if (o.size() > 5 && o.substr(o.size() - 5) == ".json" &&
            read_file(o).find("\"control_points\"") != std::string::npos) {
          const Surface s = io::read_surface_json(o);  // throws on non-finite numbers
          for (const Point& q : s.control) EXPECT_TRUE(q.allFinite());
        }
      }
    }
  }
  fs::permissions(base, fs::perms::all);
  fs::remove_all(base);
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string n = info.param.name;
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInput, ::testing::ValuesIn(load_cases()), case_name);

TEST(BadInputCorpus, IsLargeAndCoversEveryCode) {
  const auto cases = load_cases();
  std::set<std::string> names;
  std::map<int, int> per_code;
  for (const auto& c : cases) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate case name " << c.name;
    ++per_code[c.exit_code];
    if (c.input.empty() || c.input[0] == '@' || c.input == "-") continue;
    const std::string file = c.input[0] == '<' ? c.input.substr(1) : c.input;
    EXPECT_TRUE(fs::exists(kCorpus + "/" + file)) << c.name << ": no file " << file;
  }
  EXPECT_GE(cases.size(), 40u);
  for (int code : {0, 2, 3, 4, 5, 6, 7})
    EXPECT_GT(per_code[code], 0) << "no case for exit " << code;
}

}  // namespace
}  // namespace sfit::test
