#pragma once
// The STEP reader's answer, as bytes between the reading process
// (cairn-step-reader, src/io/step/) and Cairn (step_reader.cpp): 'M' and the
// model, or 'E' and an InputError's file, JSON path and message. Private to
// the io stage.

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cairn/io/step_reader.h"

namespace cairn::step_codec {

class Writer {
 public:
  void Byte(char c) { out_ += c; }
  void U64(std::uint64_t x) { out_.append(reinterpret_cast<const char*>(&x), sizeof x); }
  void F64(double x) { out_.append(reinterpret_cast<const char*>(&x), sizeof x); }
  void Str(const std::string& s) {
    U64(s.size());
    out_ += s;
  }
  const std::string& str() const { return out_; }

 private:
  std::string out_;
};

// Reads what Writer wrote. @throws std::runtime_error on a short answer.
class Reader {
 public:
  explicit Reader(const std::string& in) : in_(in) {}
  char Byte() { return Take(1)[0]; }
  std::uint64_t U64() {
    std::uint64_t x = 0;
    std::memcpy(&x, Take(sizeof x), sizeof x);
    return x;
  }
  double F64() {
    double x = 0;
    std::memcpy(&x, Take(sizeof x), sizeof x);
    return x;
  }
  std::string Str() {
    const std::uint64_t size = U64();
    if (size > in_.size()) throw std::runtime_error("STEP reader: a short answer from its process");
    return std::string(Take(static_cast<size_t>(size)), static_cast<size_t>(size));
  }
  // A count of items of at least `bytes` each: no more than the bytes left.
  size_t Count(size_t bytes) {
    const std::uint64_t count = U64();
    if (count > (in_.size() - pos_) / bytes)
      throw std::runtime_error("STEP reader: a short answer from its process");
    return static_cast<size_t>(count);
  }

 private:
  const char* Take(size_t size) {
    if (size > in_.size() - pos_)
      throw std::runtime_error("STEP reader: a short answer from its process");
    const char* p = in_.data() + pos_;
    pos_ += size;
    return p;
  }
  const std::string& in_;
  size_t pos_ = 0;
};

inline void WriteModel(const StepModel& model, Writer& w) {
  w.Byte('M');
  w.F64(model.length_unit);
  w.Str(model.def.name);
  w.F64(model.def.tolerance);
  w.Str(model.def.tolerance_option);
  w.U64(model.def.parts.size());
  for (size_t k = 0; k < model.def.parts.size(); ++k) {
    const PartDef& part = model.def.parts[k];
    w.Str(part.name);
    w.U64(part.polyhedron->vertices.size());
    for (const Vector3& v : part.polyhedron->vertices) w.F64(v.x()), w.F64(v.y()), w.F64(v.z());
    w.U64(part.polyhedron->faces.size());
    for (const std::vector<int>& face : part.polyhedron->faces) {
      w.U64(face.size());
      for (const int v : face) w.U64(static_cast<std::uint64_t>(v));
    }
    const StepPartReport& r = model.parts[k];
    w.Str(r.name);
    w.Byte(r.approximated ? 1 : 0);
    w.U64(static_cast<std::uint64_t>(r.exact_faces));
    w.U64(static_cast<std::uint64_t>(r.tessellated_faces));
    w.F64(r.mesh_tolerance);
    w.F64(r.exact_volume);
    w.F64(r.exact_area);
    w.F64(r.volume);
    w.Str(r.fallback);
  }
  w.U64(model.common_volumes.size());
  for (const double v : model.common_volumes) w.F64(v);
}

inline StepModel ReadModel(Reader& r) {
  StepModel model;
  model.length_unit = r.F64();
  model.def.name = r.Str();
  model.def.tolerance = r.F64();
  model.def.tolerance_option = r.Str();
  const size_t parts = r.Count(8);
  for (size_t k = 0; k < parts; ++k) {
    PartDef part;
    part.name = r.Str();
    PolyhedronDef poly;
    poly.vertices.resize(r.Count(24));
    for (Vector3& v : poly.vertices) {
      const double x = r.F64(), y = r.F64(), z = r.F64();
      v = Vector3(x, y, z);
    }
    poly.faces.resize(r.Count(8));
    for (std::vector<int>& face : poly.faces) {
      face.resize(r.Count(8));
      for (int& v : face) v = static_cast<int>(r.U64());
    }
    part.polyhedron = std::move(poly);
    model.def.parts.push_back(std::move(part));
    StepPartReport report;
    report.name = r.Str();
    report.approximated = r.Byte() != 0;
    report.exact_faces = static_cast<int>(r.U64());
    report.tessellated_faces = static_cast<int>(r.U64());
    report.mesh_tolerance = r.F64();
    report.exact_volume = r.F64();
    report.exact_area = r.F64();
    report.volume = r.F64();
    report.fallback = r.Str();
    model.parts.push_back(report);
  }
  model.common_volumes.resize(r.Count(8));
  for (double& v : model.common_volumes) v = r.F64();
  return model;
}

// The pairs of parts the reading process joins (StepReadOptions::fastened,
// touching, common_volumes_of), as an argument of cairn-step-reader: the
// bytes of Writer in hexadecimal (names may hold any byte).
inline std::string EncodePairs(const StepReadOptions& options) {
  Writer w;
  for (const auto* list : {&options.fastened, &options.touching, &options.common_volumes_of}) {
    w.U64(list->size());
    for (const auto& [a, b] : *list) w.Str(a), w.Str(b);
  }
  static const char* const kHex = "0123456789abcdef";
  std::string hex;
  for (const unsigned char c : w.str()) hex += kHex[c >> 4], hex += kHex[c & 15];
  return hex;
}

// EncodePairs's inverse into `options`. @throws std::runtime_error on text
// that EncodePairs did not write.
inline void DecodePairs(const std::string& hex, StepReadOptions& options) {
  if (hex.size() % 2 != 0) throw std::runtime_error("STEP reader: bad pairs argument");
  std::string bytes;
  for (size_t k = 0; k < hex.size(); k += 2) {
    const auto digit = [&](char c) {
      if (c >= '0' && c <= '9') return c - '0';
      if (c >= 'a' && c <= 'f') return c - 'a' + 10;
      throw std::runtime_error("STEP reader: bad pairs argument");
    };
    bytes += static_cast<char>(digit(hex[k]) * 16 + digit(hex[k + 1]));
  }
  Reader r(bytes);
  for (auto* list : {&options.fastened, &options.touching, &options.common_volumes_of}) {
    list->resize(r.Count(16));
    for (auto& [a, b] : *list) a = r.Str(), b = r.Str();
  }
}

// An InputError as the answer.
inline void WriteError(const std::string& file, const std::string& json_path,
                       const std::string& message, Writer& w) {
  w.Byte('E');
  w.Str(file);
  w.Str(json_path);
  w.Str(message);
}

}  // namespace cairn::step_codec
