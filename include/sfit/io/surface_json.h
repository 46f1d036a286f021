// The surface and report JSON of docs/surface-json.md, read and written as text.
#pragma once

#include <string>
#include <string_view>

#include "sfit/surface.h"
#include "sfit/surface_fit.h"

namespace sfit::io {

/// The contract version a file with non-uniform knots carries under "version" (a surface on
/// uniform knots is written as version 1, without the key, byte for byte as before).
inline constexpr int kNonUniformVersion = 2;

/// The surface as JSON text in the contract's form (full knot vectors, full control arrays, a
/// periodic direction with its wrap copies, `periodic` flags; doubles round-trip exactly),
/// with the fit report under "report" when `report` is given. `indent` < 0: one line.
std::string surface_to_json_text(const Surface& surface, const FitReport* report = nullptr,
                                 int indent = -1);

/// The report alone as JSON text: the contract's keys plus sfit's extras.
std::string report_to_json_text(const FitReport& report, int indent = 2);

/// Reads a surface from JSON text in the contract's form; `name` is used in messages.
/// Throws Error(kInputSyntax) for malformed JSON and Error(kInputData) for a surface that
/// breaks the contract (knot vector lengths, knots that decrease, repeat more than the degree
/// or (open) lack degree + 1 equal end knots, a periodic vector whose spacing does not repeat, a
/// periodic direction whose wrap copies differ, non-finite numbers).
Surface surface_from_json_text(std::string_view text, const std::string& name);

/// Reads a surface file written by write_surface_json (or any tool keeping the contract).
Surface read_surface_json(const std::string& path);

/// The text write_surface_json() writes (for standard output).
std::string surface_json_text(const Surface& surface, const FitReport* report = nullptr);

/// Writes {surface..., "report": {...}} atomically (report omitted when null).
void write_surface_json(const std::string& path, const Surface& surface,
                        const FitReport* report = nullptr);
/// Writes the report alone, atomically.
void write_report_json(const std::string& path, const FitReport& report);

}  // namespace sfit::io
