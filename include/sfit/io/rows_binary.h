// A binary form of .rows for big inputs (10^7 points and more): read with a handful of
// system calls and no parsing.
//
// Layout (little-endian): 8 bytes "SFITROWS", uint32 version (1), uint32 flags (0),
// uint64 M (rows), uint64 P (points), M x uint64 row lengths (each >= 1, summing to P),
// then P x 3 float64 x, y, z. File size = 32 + 8 M + 24 P exactly. Flags bit 0 (weighted,
// docs/seams.md): P float64 weights follow, one per point, and the size is 32 + 8 M + 32 P.
#pragma once

#include <string>

#include "sfit/io/rows_reader.h"
#include "sfit/rows.h"

namespace sfit::io {

/// True if `path` ends in ".srows" (the binary form).
bool is_binary_rows_path(const std::string& path);

/// Reads a .srows file ("-" is not accepted: the size is checked against the header).
/// Throws Error: kInputUnreadable (missing, unreadable), kInputSyntax (bad magic, version,
/// or a size that does not match the header: truncated or padded), kInputData (a row of
/// zero points, a non-finite coordinate, naming row and point).
RowsFile read_rows_binary(const std::string& path);

/// Writes `rows` as .srows, atomically.
void write_rows_binary(const std::string& path, const Rows& rows);

}  // namespace sfit::io
