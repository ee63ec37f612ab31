#pragma once
/// @file
/// Readers for LCP problem files, used by tests and benchmarks:
///  - the plain row-major format: optional '#' comment lines, n, then the n
///    rows of M, then q;
///  - Siconos' LinearComplementarityProblem `.dat` format (dense, stored
///    column-major, or sparse-block), as written by
///    linearComplementarity_printInFile.

#include <string>

#include "cairn/core/types.h"

namespace cairn {

/// One LCP(M, q) read from a file.
struct LcpProblem {
  MatrixX M;  ///< (n x n)
  VectorX q;  ///< (n)
};

/// Reads a plain-format LCP file. @throws InputError on a malformed file.
LcpProblem ReadLcpPlain(const std::string& path);

/// Reads a Siconos `.dat` LCP file (storage 0 dense column-major, or 1 sparse
/// block). @throws InputError on a malformed or unsupported file.
LcpProblem ReadLcpSiconos(const std::string& path);

/// Chooses the reader by extension: `.dat` → Siconos, anything else → plain.
LcpProblem ReadLcpFile(const std::string& path);

}  // namespace cairn
