#include "occt_common.h"

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cctype>
#include <cmath>
#include <utility>
#include <vector>

namespace sfit::exchange::detail {

namespace {

void knots(const KnotVector& kv, int degree, int count, bool periodic, TColStd_Array1OfReal& k,
           TColStd_Array1OfInteger& m) {
  if (!kv.uniform()) {  // the distinct knots with their multiplicities, as they are
    std::vector<double> values;
    std::vector<int> mults;
    kv.breaks(values, mults);
    const int n = static_cast<int>(values.size());
    k.Resize(1, n, false);
    m.Resize(1, n, false);
    for (int i = 0; i < n; ++i) {
      k(i + 1) = values[static_cast<std::size_t>(i)];
      m(i + 1) = mults[static_cast<std::size_t>(i)];
    }
    return;
  }
  const int n = periodic ? count + 1 : count - degree + 1;
  k.Resize(1, n, false);
  m.Resize(1, n, false);
  for (int i = 0; i < n; ++i) {
    k(i + 1) = i;
    m(i + 1) = (!periodic && (i == 0 || i == n - 1)) ? degree + 1 : 1;
  }
}

}  // namespace

Handle(Geom_BSplineSurface) to_occt(const Surface& s) {
  TColgp_Array2OfPnt poles(1, s.count_u, 1, s.count_v);
  for (int i = 0; i < s.count_u; ++i)
    for (int j = 0; j < s.count_v; ++j) {
      const Point& p = s.at(i, j);
      poles(i + 1, j + 1) = gp_Pnt(p.x(), p.y(), p.z());
    }
  TColStd_Array1OfReal ku(1, 1), kv(1, 1);
  TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
  knots(s.knots_u, s.degree_u, s.count_u, s.periodic_u, ku, mu);
  knots(s.knots_v, s.degree_v, s.count_v, s.periodic_v, kv, mv);
  return new Geom_BSplineSurface(poles, ku, kv, mu, mv, s.degree_u, s.degree_v, s.periodic_u,
                                 s.periodic_v);
}

void quiet_occt() {
  static const bool done = [] {
    const Message_SequenceOfPrinters& printers = Message::DefaultMessenger()->Printers();
    for (Message_SequenceOfPrinters::Iterator it(printers); it.More(); it.Next())
      it.Value()->SetTraceLevel(Message_Fail);
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    return true;
  }();
  (void)done;
}

const Unit* unit_named(const std::string& ours) {
  for (const Unit& u : kUnits)
    if (ours == u.ours) return &u;
  return nullptr;
}

const Unit* unit_of_size(double mm) {
  for (const Unit& u : kUnits)
    if (std::abs(mm - u.mm) <= 1e-9 * u.mm) return &u;
  return nullptr;
}

const Unit* step_unit(std::string name) {
  for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  static const std::pair<const char*, const char*> names[] = {
      {"MILLIMETRE", "mm"}, {"CENTIMETRE", "cm"}, {"KILOMETRE", "km"}, {"MICROMETRE", "um"},
      {"METRE", "m"},       {"INCH", "in"},       {"FOOT", "ft"},      {"MILE", "mi"}};
  for (const auto& [occt, ours] : names)
    if (name.find(occt) != std::string::npos) return unit_named(ours);
  return nullptr;
}

const Unit* iges_unit(int flag) {
  static const std::pair<int, const char*> flags[] = {{1, "in"}, {2, "mm"}, {4, "ft"}, {5, "mi"},
                                                      {6, "m"},  {7, "km"}, {9, "um"}, {10, "cm"}};
  for (const auto& [iges, ours] : flags)
    if (flag == iges) return unit_named(ours);
  return nullptr;
}

std::string describe(const Standard_Failure& f) {
  const char* msg = f.GetMessageString();
  return std::string(f.DynamicType()->Name()) + (msg && *msg ? std::string(": ") + msg : "");
}

}  // namespace sfit::exchange::detail
