// The registries of fit methods and parameter rules (fit_registry.h), and the built-ins: one
// line each below. A new method or rule is its own file plus one line here.
#include "fit_registry.h"

#include <deque>
#include <mutex>
#include <utility>

#include "sfit/error.h"
#include "sfit/fit_registry.h"
#include "surface_fitter.h"

namespace sfit::detail {
namespace {

// Ids handed to registered (not built-in) methods and rules start here, clear of the enums.
constexpr int kFirstRegistered = 64;

template <class Entry>
struct Registry {
  std::deque<Entry> entries;  // never shrinks: names and entries stay where they are
  std::deque<bool> active;
  int next_id = kFirstRegistered;
};

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}
long generation = 0;  // under registry_mutex()

std::vector<double> row_positions(Parametrization rule, std::span<const Point> points,
                                  bool periodic) {
  return normalized_positions(points, rule, periodic);
}

Registry<MethodEntry>& method_registry() {
  static Registry<MethodEntry> r = [] {
    Registry<MethodEntry> m;
    auto add = [&](FitMethod id, std::string name, std::string help, MethodFunction f,
                   StateFunction incremental = {}) {
      m.entries.push_back(
          MethodEntry{id, std::move(name), std::move(help), std::move(f), std::move(incremental)});
      m.active.push_back(true);
    };
    // The built-in methods, one line each.
    add(FitMethod::kSurface, "surface",
        "the fewest nu x nv whose surface holds T, searched over all points at once; never more "
        "than sfit01",
        fit_surface_search);
    add(FitMethod::kSfit01, "sfit01", "the paper's two stages", fit_sfit01_method, sfit01_state);
    return m;
  }();
  return r;
}

Registry<RuleEntry>& rule_registry() {
  static Registry<RuleEntry> r = [] {
    Registry<RuleEntry> m;
    auto add = [&](Parametrization id, std::string name, std::string help, bool row_rule) {
      PositionFunction f;
      if (row_rule)
        f = [id](std::span<const Point> p, bool periodic) {
          return row_positions(id, p, periodic);
        };
      m.entries.push_back(RuleEntry{id, std::move(name), std::move(help), std::move(f)});
      m.active.push_back(true);
    };
    // The built-in rules (and the two choices that are none), one line each.
    add(Parametrization::kPaper, "paper", "SFIT01's, by the point's index", false);
    add(Parametrization::kUniform, "uniform", "index", true);
    add(Parametrization::kChord, "chord", "chord length", true);
    add(Parametrization::kCentripetal, "centripetal", "", true);
    add(Parametrization::kGeometric, "geometric",
        "each point's projection onto a plane or, closed rows, an axis; --method surface only",
        false);
    add(Parametrization::kFewest, "fewest", "tries the rules, keeps the fewest control points",
        false);
    add(Parametrization::kAuto, "auto",
        "geometric and the four with --method surface, paper with --method sfit01", false);
    return m;
  }();
  return r;
}

template <class Entry, class Id>
const Entry* find_id(Registry<Entry>& r, Id id) {
  for (std::size_t k = 0; k < r.entries.size(); ++k)
    if (r.active[k] && r.entries[k].id == id) return &r.entries[k];
  return nullptr;
}

template <class Entry>
const Entry* find_name(Registry<Entry>& r, std::string_view name) {
  for (std::size_t k = 0; k < r.entries.size(); ++k)
    if (r.active[k] && r.entries[k].name == name) return &r.entries[k];
  return nullptr;
}

template <class Entry>
std::vector<Entry> listed(Registry<Entry>& r) {
  std::vector<Entry> out;
  for (std::size_t k = 0; k < r.entries.size(); ++k)
    if (r.active[k]) out.push_back(r.entries[k]);
  return out;
}

template <class Entry>
std::string names_of(Registry<Entry>& r) {
  std::string s;
  for (std::size_t k = 0; k < r.entries.size(); ++k)
    if (r.active[k]) s += (s.empty() ? "" : ", ") + r.entries[k].name;
  return s;
}

template <class Entry, class Fn>
auto add_entry(Registry<Entry>& r, std::string name, std::string help, Fn f, const char* option,
               bool automatic = false) {
  if (name.empty() || find_name(r, name))
    throw Error(ErrorCode::kUsage,
                std::string("a ") + option + " named \"" + name + "\" is registered already" +
                    (name.empty() ? " (an empty name)" : ""),
                Place{.option = option});
  const auto id = static_cast<decltype(Entry{}.id)>(r.next_id++);
  Entry e{id, std::move(name), std::move(help), std::move(f)};
  if constexpr (requires { e.automatic; }) e.automatic = automatic;
  r.entries.push_back(std::move(e));
  r.active.push_back(true);
  ++generation;
  return id;
}

template <class Entry, class Id>
void remove_entry(Registry<Entry>& r, Id id) {
  if (static_cast<int>(id) < kFirstRegistered) return;  // built-ins stay
  for (std::size_t k = 0; k < r.entries.size(); ++k)
    if (r.active[k] && r.entries[k].id == id) {
      r.active[k] = false;  // the name is free; its text stays where it is (string_views)
      ++generation;
    }
}

}  // namespace

MethodEntry method_entry(FitMethod id) {
  const std::lock_guard lock(registry_mutex());
  if (const MethodEntry* e = find_id(method_registry(), id)) return *e;
  throw Error(ErrorCode::kUsage,
              "no method registered as " + std::to_string(static_cast<int>(id)) +
                  "; registered: " + names_of(method_registry()),
              Place{.option = "method"}, {static_cast<double>(id)});
}

MethodEntry method_entry(std::string_view name) {
  const std::lock_guard lock(registry_mutex());
  if (const MethodEntry* e = find_name(method_registry(), name)) return *e;
  throw Error(
      ErrorCode::kUsage,
      "no method named \"" + std::string(name) + "\"; registered: " + names_of(method_registry()),
      Place{.option = "method"});
}

const RuleEntry* rule_entry(Parametrization id) {
  const std::lock_guard lock(registry_mutex());
  return find_id(rule_registry(), id);
}

const RuleEntry* rule_entry(std::string_view name) {
  const std::lock_guard lock(registry_mutex());
  return find_name(rule_registry(), name);
}

std::string_view method_name(FitMethod id) {
  const std::lock_guard lock(registry_mutex());
  const MethodEntry* e = find_id(method_registry(), id);
  return e ? std::string_view(e->name) : std::string_view();
}

std::string_view rule_name(Parametrization id) {
  const std::lock_guard lock(registry_mutex());
  const RuleEntry* e = find_id(rule_registry(), id);
  return e ? std::string_view(e->name) : std::string_view();
}

std::vector<MethodEntry> methods() {
  const std::lock_guard lock(registry_mutex());
  return listed(method_registry());
}

std::vector<RuleEntry> rules() {
  const std::lock_guard lock(registry_mutex());
  return listed(rule_registry());
}

std::vector<Parametrization> automatic_rules() {
  const std::lock_guard lock(registry_mutex());
  std::vector<Parametrization> out;
  for (const RuleEntry& e : listed(rule_registry()))
    if (e.automatic) out.push_back(e.id);
  return out;
}

long registry_generation() {
  const std::lock_guard lock(registry_mutex());
  return generation;
}

FitMethod register_method(std::string name, std::string help, MethodFunction fit) {
  const std::lock_guard lock(registry_mutex());
  return add_entry(method_registry(), std::move(name), std::move(help), std::move(fit), "method");
}

Parametrization register_rule(std::string name, std::string help, PositionFunction positions,
                              bool automatic) {
  const std::lock_guard lock(registry_mutex());
  return add_entry(rule_registry(), std::move(name), std::move(help), std::move(positions),
                   "parameters", automatic);
}

void unregister_method(FitMethod id) {
  const std::lock_guard lock(registry_mutex());
  remove_entry(method_registry(), id);
}

void unregister_rule(Parametrization id) {
  const std::lock_guard lock(registry_mutex());
  remove_entry(rule_registry(), id);
}

}  // namespace sfit::detail

namespace sfit {

// The public face (sfit/fit_registry.h): handles over the registries above.

RegisteredMethod::RegisteredMethod(std::string name, std::string help, FitMethodFunction fit)
    : id_(detail::register_method(std::move(name), std::move(help),
                                  [fit = std::move(fit)](const detail::FitSpec& s) {
                                    const detail::Centring& c = s.centring;
                                    return fit(MethodInput{.rows = s.rows,
                                                           .options = s.options,
                                                           .seam_offsets = s.seam_offsets,
                                                           .centred = c.centred,
                                                           .centre = c.centre,
                                                           .box = c.box,
                                                           .roundoff = c.roundoff,
                                                           .threads = c.threads});
                                  })),
      owns_(true) {}

RegisteredMethod::~RegisteredMethod() {
  if (owns_) detail::unregister_method(id_);
}

RegisteredMethod::RegisteredMethod(RegisteredMethod&& other) noexcept
    : id_(other.id_), owns_(std::exchange(other.owns_, false)) {}

RegisteredMethod& RegisteredMethod::operator=(RegisteredMethod&& other) noexcept {
  if (this != &other) {
    if (owns_) detail::unregister_method(id_);
    id_ = other.id_;
    owns_ = std::exchange(other.owns_, false);
  }
  return *this;
}

RegisteredRule::RegisteredRule(std::string name, std::string help, RowRuleFunction positions,
                               RuleUse use)
    : id_(detail::register_rule(std::move(name), std::move(help), std::move(positions),
                                use == RuleUse::kAlsoAuto)),
      owns_(true) {}

RegisteredRule::~RegisteredRule() {
  if (owns_) detail::unregister_rule(id_);
}

RegisteredRule::RegisteredRule(RegisteredRule&& other) noexcept
    : id_(other.id_), owns_(std::exchange(other.owns_, false)) {}

RegisteredRule& RegisteredRule::operator=(RegisteredRule&& other) noexcept {
  if (this != &other) {
    if (owns_) detail::unregister_rule(id_);
    id_ = other.id_;
    owns_ = std::exchange(other.owns_, false);
  }
  return *this;
}

}  // namespace sfit
