#include "sfit/io/formats.h"

namespace sfit::io {
namespace {

// Which optional parts this build has: set on sfit_io by src/exchange and src/render.
#ifdef SFIT_FORMATS_MESH
constexpr bool kMesh = true;
#else
constexpr bool kMesh = false;
#endif
#ifdef SFIT_FORMATS_CAD
constexpr bool kCad = true;
#else
constexpr bool kCad = false;
#endif
#ifdef SFIT_FORMATS_PNG
constexpr bool kPng = true;
#else
constexpr bool kPng = false;
#endif

bool has(FormatPart p) {
  switch (p) {
    case FormatPart::kCore:
      return true;
    case FormatPart::kMesh:
      return kMesh;
    case FormatPart::kCad:
      return kCad;
    case FormatPart::kRender:
      return kPng;
  }
  return false;
}

std::vector<Format> make() {
  using K = FormatKind;
  using P = FormatPart;
  std::vector<Format> f = {
      {FormatId::kRows,
       "rows",
       {"rows"},
       "rows of points as 'x y z' text lines, a blank line between rows "
       "(docs/rows-format.md)",
       K::kRows,
       true,
       false,
       P::kCore},
      {FormatId::kBinaryRows,
       "binary rows",
       {"srows"},
       "the same rows in sfit's binary form (written by 'sfit pack')",
       K::kRows,
       true,
       true,
       P::kCore},
      {FormatId::kCsv,
       "CSV",
       {"csv"},
       "rows of points as x,y,z columns (an optional row column or blank lines "
       "separate rows)",
       K::kRows,
       true,
       false,
       P::kCore},
      {FormatId::kSurfaceJson,
       "surface JSON",
       {"json"},
       "the fitted B-spline surface and its report "
       "(docs/surface-json.md)",
       K::kSurface,
       true,
       true,
       P::kCore},
      {FormatId::kStep,
       "STEP",
       {"step", "stp"},
       "AP214 B-spline surface (written); section curves, one row "
       "each (read)",
       K::kSurface,
       true,
       true,
       P::kCad},
      {FormatId::kIges,
       "IGES",
       {"igs", "iges"},
       "IGES 5.3 trimmed B-spline surface (written); section curves, "
       "one row each (read)",
       K::kSurface,
       true,
       true,
       P::kCad},
      {FormatId::kObj,
       "OBJ",
       {"obj"},
       "Wavefront OBJ: triangle mesh, or the free-form B-spline with --obj-freeform",
       K::kSurface,
       false,
       true,
       P::kMesh},
      {FormatId::kStl,
       "STL",
       {"stl"},
       "binary STL triangle mesh (float32 coordinates)",
       K::kSurface,
       false,
       true,
       P::kMesh},
      {FormatId::kPly,
       "PLY",
       {"ply"},
       "binary PLY triangle mesh with normals",
       K::kSurface,
       false,
       true,
       P::kMesh},
      {FormatId::kVtk,
       "VTK",
       {"vtk"},
       "legacy VTK polydata mesh for ParaView (--fields: curvature, deviation)",
       K::kSurface,
       false,
       true,
       P::kMesh},
      {FormatId::kVts,
       "VTS",
       {"vts"},
       "VTK XML structured grid for ParaView (--fields: curvature, deviation)",
       K::kSurface,
       false,
       true,
       P::kMesh},
      {FormatId::kPng,
       "PNG",
       {"png"},
       "a picture of the surface or of one row ('sfit render', 'fit --png')",
       K::kPicture,
       false,
       true,
       P::kRender},
  };
  for (Format& x : f) x.available = has(x.part);
  return f;
}

}  // namespace

const std::vector<Format>& formats() {
  static const std::vector<Format> f = make();
  return f;
}

const Format* find_format(std::string_view extension) {
  for (const Format& f : formats())
    for (std::string_view e : f.extensions)
      if (e == extension) return &f;
  return nullptr;
}

std::string_view part_name(FormatPart part) {
  switch (part) {
    case FormatPart::kCore:
      return "the core";
    case FormatPart::kMesh:
      return "the mesh part (sfit_mesh)";
    case FormatPart::kCad:
      return "the CAD part (OpenCASCADE)";
    case FormatPart::kRender:
      return "the picture part (libpng)";
  }
  return "";
}

std::string extension_list(FormatKind kind, bool reads) {
  std::string out;
  for (const Format& f : formats()) {
    if (f.kind != kind || !f.available || !(reads ? f.reads : f.writes)) continue;
    for (std::string_view e : f.extensions) out += (out.empty() ? "." : ", .") + std::string(e);
  }
  return out;
}

}  // namespace sfit::io
