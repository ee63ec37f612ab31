#include "cairn/report/blocking_report.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "cairn/core/tolerances.h"
#include "report/report_common.h"

namespace cairn {

namespace {

using report_internal::Vec;

constexpr double kDegrees = 180.0 / std::numbers::pi;

// An angle in degrees, without floating-point dust (1e-9 degree).
double Degrees(double radians) {
  const double d = radians * kDegrees;
  const double r = std::round(d);
  return std::abs(d - r) < numeric::kParameterSlack ? r : d;
}

std::string Fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, std::abs(x) < 5e-13 ? 0.0 : x);
  return buf;
}

// The arcs of a graph as [blocked, blocker] names, in part order.
nlohmann::json ArcsJson(const Assembly& assembly, const BlockingGraph& g) {
  nlohmann::json arcs = nlohmann::json::array();
  for (int i = 0; i < static_cast<int>(g.blockers.size()); ++i)
    for (const int j : g.blockers[i])
      arcs.push_back(nlohmann::json::array({assembly.part(i).name, assembly.part(j).name}));
  return arcs;
}

std::string DirectionText(const Vector3& d, int dim) {
  std::string s = "(" + Fmt("%.4g", d.x()) + ", " + Fmt("%.4g", d.y());
  if (dim == 3) s += ", " + Fmt("%.4g", d.z());
  return s + ")";
}

std::string Pad(std::string s, size_t width) {
  // Width in characters (UTF-8: count the bytes that start a character).
  size_t chars = 0;
  for (const char c : s) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  if (chars < width) s.append(width - chars, ' ');
  return s;
}

}  // namespace

nlohmann::json NdbgToJson(const Assembly& assembly, const Ndbg& ndbg,
                          const ReportOptions& options) {
  const int dim = ndbg.dimension;
  nlohmann::json doc;
  doc["scene"] = options.scene_file;
  doc["name"] = assembly.name();
  doc["dimension"] = dim;
  nlohmann::json without = nlohmann::json::array();
  for (const int i : options.without) without.push_back(assembly.part(i).name);
  doc["without"] = without;
  nlohmann::json normals = nlohmann::json::array();
  for (const Vector3& n : ndbg.normals) normals.push_back(Vec(n, dim));
  doc["normals"] = normals;
  nlohmann::json cells = nlohmann::json::array();
  for (const NdbgCell& cell : ndbg.cells) {
    nlohmann::json c;
    c["dimension"] = cell.cell_dimension;
    c["direction"] = Vec(cell.direction, dim);
    if (dim == 2)
      c["angles_deg"] = nlohmann::json::array({Degrees(cell.angle_from), Degrees(cell.angle_to)});
    else
      c["signs"] = cell.signs;
    c["infinitesimal"] = ArcsJson(assembly, cell.infinitesimal);
    c["infinity"] = ArcsJson(assembly, cell.infinity);
    nlohmann::json removable = nlohmann::json::array();
    for (const int i : cell.removable) removable.push_back(assembly.part(i).name);
    c["removable"] = removable;
    cells.push_back(c);
  }
  doc["cells"] = cells;
  return doc;
}

std::string NdbgHeadline(const Assembly& assembly, const Ndbg& ndbg, const ReportOptions& options) {
  const int dim = ndbg.dimension;
  std::ostringstream os;
  os << (assembly.name().empty() ? options.scene_file : assembly.name()) << ": NDBG (" << dim
     << "-D), " << ndbg.cells.size() << " cell" << (ndbg.cells.size() == 1 ? "" : "s") << ", "
     << ndbg.normals.size() << " distinct contact normal" << (ndbg.normals.size() == 1 ? "" : "s")
     << "\n";
  if (!options.without.empty()) {
    os << "without:";
    for (const int i : options.without) os << ' ' << assembly.part(i).name;
    os << '\n';
  }
  return os.str();
}

std::string NdbgToText(const Assembly& assembly, const Ndbg& ndbg, const ReportOptions& options) {
  const int dim = ndbg.dimension;
  std::ostringstream os;
  os << NdbgHeadline(assembly, ndbg, options);
  os << "per cell: its directions, a representative direction, the parts that can leave alone\n"
     << "to infinity, and which parts are blocked by which (* also infinitesimally)\n";
  constexpr int kMaxBlocked = 12;  // the JSON document has them all
  for (const NdbgCell& cell : ndbg.cells) {
    std::string where;
    if (dim == 2) {
      const double from = Degrees(cell.angle_from), to = Degrees(cell.angle_to);
      if (cell.cell_dimension == 0)
        where = Fmt("%.6g", from) + "°";
      else if (ndbg.cells.size() == 1)
        where = "all directions";
      else
        where = "(" + Fmt("%.6g", from) + "°, " + Fmt("%.6g", to) + "°)";
    } else {
      static const char* kKinds[] = {"vertex", "arc", "face"};
      where = std::string(kKinds[cell.cell_dimension]) + " [";
      for (const int s : cell.signs) where += s > 0 ? '+' : (s < 0 ? '-' : '0');
      where += "]";
    }
    os << "  " << Pad(where, 22) << Pad(DirectionText(cell.direction, dim), 24) << "leave: ";
    if (cell.removable.empty()) os << "none";
    for (size_t k = 0; k < cell.removable.size(); ++k)
      os << (k ? ", " : "") << assembly.part(cell.removable[k]).name;
    os << "   blocked: ";
    int shown = 0, blocked = 0;
    for (int i = 0; i < static_cast<int>(cell.infinity.blockers.size()); ++i) {
      const std::vector<int>& by = cell.infinity.blockers[i];
      if (by.empty()) continue;
      ++blocked;
      if (shown == kMaxBlocked) continue;
      os << (shown ? "; " : "") << assembly.part(i).name << " by ";
      for (size_t k = 0; k < by.size(); ++k)
        os << (k ? ", " : "") << assembly.part(by[k]).name
           << (cell.infinitesimal.Blocks(i, by[k]) ? "*" : "");
      ++shown;
    }
    if (blocked == 0) os << "none";
    if (blocked > shown) os << "; and " << blocked - shown << " more parts";
    os << '\n';
  }
  return os.str();
}

}  // namespace cairn
