// The one format registry (sfit/io/formats.h): well formed, and what the CLI dispatches,
// lists in its help and in 'sfit formats' is exactly what it holds.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "sfit/io/formats.h"
#include "test_support.h"

namespace sfit::test {
namespace {

TEST(Formats, EveryFormatIsWellFormedAndEveryExtensionUnique) {
  std::set<std::string> seen;
  for (const io::Format& f : io::formats()) {
    EXPECT_FALSE(f.name.empty());
    EXPECT_FALSE(f.description.empty()) << f.name;
    EXPECT_FALSE(f.extensions.empty()) << f.name;
    EXPECT_TRUE(f.reads || f.writes) << f.name;
    if (f.part == io::FormatPart::kCore) {
      EXPECT_TRUE(f.available) << f.name;
    }
    for (std::string_view e : f.extensions) {
      EXPECT_TRUE(seen.insert(std::string(e)).second) << "extension ." << e << " twice";
      EXPECT_EQ(io::find_format(e), &f);
    }
  }
  EXPECT_EQ(io::find_format("xyz"), nullptr);
}

TEST(Formats, TheCliWritesEverySurfaceFormatOfTheRegistryAndListsThem) {
  const std::string dir = temp_dir();
  const std::string in = std::string(SFIT_TESTS_DIR) + "/bad_input/good.rows";
  std::string args = "fit '" + in + "' -q";
  std::vector<std::string> files;
  for (const io::Format& f : io::formats()) {
    if (!f.writes || f.kind != io::FormatKind::kSurface || !f.available) continue;
    for (std::string_view e : f.extensions) {
      files.push_back(dir + "/surface." + std::string(e));
      args += " -o '" + files.back() + "'";
    }
  }
  const sfit::test::Run r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const auto& f : files) EXPECT_GT(std::filesystem::file_size(f), 0u) << f;
  // An unknown extension lists exactly the registry's writable surface extensions.
  const sfit::test::Run bad = run_cli("fit '" + in + "' -o '" + dir + "/x.xyz'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("(known: " + io::extension_list(io::FormatKind::kSurface, false) + ")"),
            std::string::npos)
      << bad.err;
  const sfit::test::Run list = run_cli("formats");
  EXPECT_EQ(list.exit_code, 0);
  for (const io::Format& f : io::formats())
    EXPECT_NE(list.out.find(std::string(f.description)), std::string::npos) << f.name;
  const sfit::test::Run help = run_cli("fit --help");
  EXPECT_NE(help.out.find(io::extension_list(io::FormatKind::kSurface, false)), std::string::npos);
  EXPECT_NE(help.out.find(io::extension_list(io::FormatKind::kRows, true)), std::string::npos);
}

}  // namespace
}  // namespace sfit::test
