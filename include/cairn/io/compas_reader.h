#pragma once
/// @file
/// Reading block assemblies in the COMPAS JSON format of `compas_assembly` and
/// `compas_cra` (ETH Block Research Group), issue 4. This is the parsing layer
/// only: it yields the blocks as given (polygonal faces, either orientation,
/// not validated as solids) and builds no Assembly. The layouts read are
/// described in docs/compas-format.md.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/polyhedron.h"

namespace cairn {

/// One block: a node of the assembly graph.
struct CompasBlock {
  /// The node key, as written in the file ("0", "12"): unique within the
  /// assembly and what the COMPAS scripts use to name blocks.
  std::string name;
  /// Vertices and faces of the block's mesh. The vertex keys of the file are
  /// renumbered 0..n−1 in increasing key order; faces keep their vertex order.
  PolyhedronDef shape;
  /// The node's `is_support` (or the graph's default for it): a fixed block.
  bool is_support = false;
  /// The node's `density` when the file gives one (callers use 1 otherwise).
  std::optional<double> density;
};

/// The blocks of a COMPAS assembly, in increasing node-key order (numeric keys
/// by value, before any non-numeric keys, which sort as text).
struct CompasAssembly {
  /// The assembly's `attributes.name` ("Assembly", "CRA_Assembly"), or "".
  std::string name;
  std::vector<CompasBlock> blocks;
};

/// Converts a parsed COMPAS assembly document (COMPAS 2 `dtype`/`data`
/// wrappers, or the COMPAS 1 `dtype`/`value` wrapper and bare data) to its
/// blocks, checking structure and types on the way.
/// @throws InputError naming `file` and the JSON path of the first fault.
CompasAssembly ParseCompasAssembly(const nlohmann::json& doc, const std::string& file);

/// Reads and parses a COMPAS assembly file. @throws InputError (unreadable
/// file, JSON syntax error with its line and column, repeated keys, or any
/// fault of ParseCompasAssembly).
CompasAssembly ReadCompasAssembly(const std::string& path);

}  // namespace cairn
