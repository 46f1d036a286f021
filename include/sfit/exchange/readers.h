// Section curves from CAD files as rows of points: the lofting workflow.
#pragma once

#include <string>
#include <vector>

#include "sfit/rows.h"

namespace sfit::exchange {

/// True for the extensions read_sections() handles: .step, .stp, .igs, .iges.
bool is_exchange_input(const std::string& path);

/// Rows read from a CAD file. `first_line` is empty: STEP/IGES entities have no useful line
/// numbers, so messages name the row (the curve, in file order) instead.
struct SectionsFile {
  Rows rows;
  std::vector<long> first_line;
  std::string name;
  std::vector<bool> closed;  ///< per row: the curve is closed (its last sample dropped)
  std::string units;         ///< the file's length unit (mm, m, in, ...): coordinates are in it
};

/// Each curve gets as many samples as a chordal deflection of kSectionDeflection times the
/// bounding-box diagonal of all curves needs (GCPnts_QuasiUniformDeflection), at least
/// kMinSectionSamples, placed uniformly in arc length (GCPnts_QuasiUniformAbscissa), so the
/// fit's chord-length parameters stay even.
inline constexpr double kSectionDeflection = 1e-5;
inline constexpr int kMinSectionSamples = 50;

/// How read_sections() runs OpenCASCADE.
struct SectionReadOptions {
  /// In a child process (fork): a crash, a signal or a hang of the CAD kernel on a hostile
  /// file becomes Error(kInputUnreadable) "cannot read the file: ...", never the caller's end.
  bool isolate = true;
  double timeout_seconds = 120;  ///< the child is killed after this long (isolate only)
};

/// Reads every curve of a STEP or IGES file that is not the boundary of a face (edges of
/// wires and free edges, in file order) and samples each densely into one row (see
/// kSectionDeflection). A closed curve (end = start) is a closed contour: its
/// last sample, equal to the first, is dropped, as in the .rows format; fit it with
/// --closed u.
/// Lengths are read in the file's own unit (SectionsFile::units; STEP: its length unit,
/// IGES: the global section's unit flag), never converted to millimetres.
/// A file whose top-level curve entities do not all translate is refused (kInputData, the
/// entity named); every coordinate is checked finite and within |x| <= 1e150.
/// Throws Error: kInputUnreadable (missing, a directory, unreadable, the CAD kernel crashed
/// or hung on it), kInputSyntax (not a STEP/IGES file OCCT can parse), kInputData (no section
/// curves, e.g. only faces; an untranslatable curve; a point out of range).
SectionsFile read_sections(const std::string& path, const SectionReadOptions& options = {});

}  // namespace sfit::exchange
