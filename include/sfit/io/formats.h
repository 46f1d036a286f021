// The one list of sfit's file formats: every input and output format with its extensions, a
// description and whether this build has it. The CLI's dispatch and help, `sfit formats`, the
// editor and the Python module read this list; a format is added here and nowhere else.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sfit::io {

/// The optional part of sfit a format needs.
enum class FormatPart {
  kCore,    ///< always built (sfit_io)
  kMesh,    ///< tessellated meshes (sfit_mesh)
  kCad,     ///< STEP/IGES through OpenCASCADE (sfit_exchange)
  kRender,  ///< PNG pictures through libpng (sfit_render)
};

/// What a file of this format holds for sfit.
enum class FormatKind {
  kRows,     ///< rows of points: the data a surface is fitted to
  kSurface,  ///< the fitted surface (or a mesh of it)
  kPicture,  ///< a picture of the surface
};

/// Each format, for dispatch.
enum class FormatId {
  kRows,
  kBinaryRows,
  kCsv,
  kSurfaceJson,
  kStep,
  kIges,
  kObj,
  kStl,
  kPly,
  kVtk,
  kVts,
  kPng,
};

struct Format {
  FormatId id;
  std::string_view name;  ///< e.g. "STEP"
  std::vector<std::string_view>
      extensions;                ///< lower case, without the dot; first is the usual one
  std::string_view description;  ///< one line
  FormatKind kind;
  bool reads = false;   ///< sfit reads it (fit/pack inputs for rows; convert/render for surfaces)
  bool writes = false;  ///< sfit writes it (-o)
  FormatPart part = FormatPart::kCore;
  bool available = false;  ///< this build has the part it needs
};

/// Every format, in the order of the README's table.
const std::vector<Format>& formats();

/// The format whose extension (lower case, without the dot) is `extension`, or nullptr.
const Format* find_format(std::string_view extension);

/// Name of a part for messages: "the CAD part (OpenCASCADE)".
std::string_view part_name(FormatPart part);

/// ".json, .step, .stp, ..." of the available formats of `kind` that sfit reads (`reads`) or
/// writes (`!reads`).
std::string extension_list(FormatKind kind, bool reads);

}  // namespace sfit::io
