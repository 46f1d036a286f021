// The option table (sfit/options.h): complete, consistent with FitOptions' defaults and the
// library's parsers, and its checks name the allowed values.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "sfit/error.h"
#include "sfit/io/options_json.h"
#include "sfit/options.h"

namespace sfit {
namespace {

OptionValue default_value(const OptionSpec& s) {
  const std::string d(s.default_value);
  switch (s.type) {
    case OptionType::kInteger:
      return std::stoll(d);
    case OptionType::kNumber:
      return std::stod(d);
    case OptionType::kFlag:
      return d == "true";
    default:
      return d;
  }
}

TEST(OptionTable, NamesAndFlagsAreUniqueAndSpelledAlike) {
  std::set<std::string> names, flags;
  for (const OptionSpec& s : option_table()) {
    EXPECT_TRUE(names.insert(std::string(s.name)).second) << s.name;
    EXPECT_TRUE(flags.insert(std::string(s.flag)).second) << s.flag;
    std::string flag = "--" + std::string(s.name);
    for (char& c : flag)
      if (c == '_') c = '-';
    if (s.name == "fold_guard") flag = "--no-fold-guard";  // the CLI turns the guard off
    EXPECT_EQ(s.flag, flag);
    EXPECT_FALSE(s.help.empty()) << s.name;
    EXPECT_EQ(find_option(s.name), &s);
  }
  EXPECT_EQ(find_option("no_such_option"), nullptr);
  // Every option of `sfit fit` (its --help), fit and output.
  for (const char* n :
       {"degree",     "degree_u",    "degree_v", "tol",  "tol_rel",      "closed",
        "search",     "parameters",  "method",   "norm", "seam",         "orient",
        "fold_guard", "rerepresent", "threads",  "mesh", "obj_freeform", "mesh_density",
        "normals",    "fields",      "units"})
    EXPECT_NE(find_option(n), nullptr) << n;
}

TEST(OptionTable, ChoicesAreNamedInTheHelpAndDefaultsAreAllowed) {
  for (const OptionSpec& s : option_table()) {
    if (s.type == OptionType::kChoice) {
      EXPECT_FALSE(s.choices.empty()) << s.name;
      bool default_allowed = false;
      for (std::string_view c : s.choices) {
        default_allowed = default_allowed || c == s.default_value;
        EXPECT_NE(s.help.find(std::string(c)), std::string::npos) << s.name << ": " << c;
      }
      EXPECT_TRUE(default_allowed) << s.name << " default " << s.default_value;
    }
    if (s.type == OptionType::kInteger || s.type == OptionType::kNumber) {
      EXPECT_LE(s.min, s.max) << s.name;
      if (!s.default_value.empty() && s.name != "mesh_density") {  // 0: automatic
        const double d = std::stod(std::string(s.default_value));
        EXPECT_GE(d, s.min) << s.name;
        EXPECT_LE(d, s.max) << s.name;
      }
    }
  }
}

// The table's defaults are the library's: applied to a fresh FitSettings they change nothing.
TEST(OptionTable, DefaultsAreFitOptionsDefaults) {
  FitSettings st;
  const FitOptions fresh;
  for (const OptionSpec& s : option_table())
    if (s.group == OptionGroup::kFit && !s.default_value.empty() && s.name != "tol_rel")
      set_fit_option(st, s.name, default_value(s), std::string(s.flag));
  const FitOptions& o = st.options;
  EXPECT_EQ(o.degree_u, fresh.degree_u);
  EXPECT_EQ(o.degree_v, fresh.degree_v);
  EXPECT_EQ(o.closed_u, fresh.closed_u);
  EXPECT_EQ(o.closed_v, fresh.closed_v);
  EXPECT_EQ(o.search, fresh.search);
  EXPECT_EQ(o.parametrization, fresh.parametrization);
  EXPECT_EQ(o.method, fresh.method);
  EXPECT_EQ(o.norm, fresh.norm);
  EXPECT_EQ(o.seam, fresh.seam);
  EXPECT_EQ(o.orient, fresh.orient);
  EXPECT_EQ(o.rerepresentation, fresh.rerepresentation);
  EXPECT_EQ(o.fold_guard, fresh.fold_guard);
  EXPECT_EQ(o.threads, fresh.threads);
  EXPECT_EQ(std::stod(std::string(find_option("tol_rel")->default_value)),
            kDefaultToleranceFraction);
  OutputSettings out;
  const OutputSettings out_fresh;
  for (const OptionSpec& s : option_table())
    if (s.group == OptionGroup::kOutput)
      set_output_option(out, s.name, default_value(s), std::string(s.flag));
  EXPECT_EQ(out.mesh, out_fresh.mesh);
  EXPECT_EQ(out.obj_freeform, out_fresh.obj_freeform);
  EXPECT_EQ(out.mesh_density, out_fresh.mesh_density);
  EXPECT_EQ(out.normals, out_fresh.normals);
  EXPECT_EQ(out.fields, out_fresh.fields);
  EXPECT_EQ(out.units, out_fresh.units);
}

// Every allowed value is accepted (the library's parser knows it); a wrong one is refused with
// every allowed value in the message, naming the place.
TEST(OptionTable, EveryChoiceParsesAndAWrongOneListsThemAll) {
  for (const OptionSpec& s : option_table()) {
    if (s.type != OptionType::kChoice) continue;
    for (std::string_view c : s.choices) {
      FitSettings st;
      OutputSettings out;
      if (s.group == OptionGroup::kFit)
        EXPECT_NO_THROW(set_fit_option(st, s.name, std::string(c), "x")) << s.name << " " << c;
      else
        EXPECT_NO_THROW(set_output_option(out, s.name, std::string(c), "x")) << s.name;
    }
    try {
      FitSettings st;
      OutputSettings out;
      if (s.group == OptionGroup::kFit)
        set_fit_option(st, s.name, std::string("bogus"), "--place");
      else
        set_output_option(out, s.name, std::string("bogus"), "--place");
      ADD_FAILURE() << s.name << " accepted 'bogus'";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kUsage);
      EXPECT_EQ(e.place().option, "--place");
      EXPECT_EQ(e.message(), "'bogus' is not one of " + choice_list(s)) << s.name;
    }
  }
}

TEST(OptionTable, LimitsAreChecked) {
  FitSettings st;
  EXPECT_THROW(set_fit_option(st, "degree", 21LL, "--degree"), Error);
  EXPECT_THROW(set_fit_option(st, "degree_v", 0LL, "--degree-v"), Error);
  EXPECT_THROW(set_fit_option(st, "threads", -1LL, "--threads"), Error);
  EXPECT_THROW(set_fit_option(st, "tol_rel", 2.0, "--tol-rel"), Error);
  EXPECT_THROW(set_fit_option(st, "tol", Point(1, -1, 1), "--tol"), Error);
  EXPECT_THROW(set_fit_option(st, "degree", std::string("3"), "--degree"), Error);  // a type
  EXPECT_THROW(set_fit_option(st, "mesh", true, "mesh"), Error);  // an output option
  set_fit_option(st, "degree", 5LL, "--degree");
  set_fit_option(st, "degree_v", 2LL, "--degree-v");
  EXPECT_EQ(st.options.degree_u, 5);
  EXPECT_EQ(st.options.degree_v, 2);
  set_fit_option(st, "tol", 0.5, "--tol");
  EXPECT_EQ(*st.tol, Point::Constant(0.5));
  OutputSettings out;
  EXPECT_THROW(set_output_option(out, "mesh_density", 2LL, "--mesh-density"), Error);
  EXPECT_THROW(set_output_option(out, "mesh_density", kMaxMeshDensity + 1LL, "--mesh-density"),
               Error);
  set_output_option(out, "mesh_density", 0LL, "--mesh-density");
  set_output_option(out, "mesh_density", static_cast<long long>(kMinMeshDensity), "x");
  EXPECT_EQ(out.mesh_density, kMinMeshDensity);
  try {
    set_fit_option(st, "no_such", true, "no_such");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("unknown option (known: degree, degree_u"), std::string::npos)
        << e.message();
  }
}

TEST(OptionTable, JsonHasEveryOptionWithItsLimits) {
  const nlohmann::json j = io::option_table_json();
  ASSERT_EQ(j.size(), option_table().size());
  for (std::size_t k = 0; k < j.size(); ++k) EXPECT_EQ(j[k]["name"], option_table()[k].name);
  const auto degree =
      *std::find_if(j.begin(), j.end(), [](auto& o) { return o["name"] == "degree"; });
  EXPECT_EQ(degree["min"], kMinFitDegree);
  EXPECT_EQ(degree["max"], kMaxFitDegree);
  EXPECT_EQ(degree["default"], 3);
  const auto params =
      *std::find_if(j.begin(), j.end(), [](auto& o) { return o["name"] == "parameters"; });
  EXPECT_EQ(params["default"], "auto");
  EXPECT_EQ(params["choices"].size(), 7u);
}

}  // namespace
}  // namespace sfit
