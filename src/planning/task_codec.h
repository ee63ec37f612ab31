#pragma once
// The bytes a planner task's result travels in between processes
// (PlanExecutor): a node check (its verdict and the normals of its contacts)
// and an edge evaluation (its trials' verdicts and failures). Doubles travel
// as their bits, so a result decoded on another process is the one computed,
// exactly: the planner's output does not depend on where a task ran.

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "cairn/core/check.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/planner.h"

namespace cairn::planning_codec {

class Writer {
 public:
  template <typename T>
  std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> Put(T v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void Put(const Vector3& v) {
    for (int k = 0; k < 3; ++k) Put(v[k]);
  }
  void Put(const std::string& s) {
    Put(static_cast<uint64_t>(s.size()));
    bytes_ += s;
  }
  template <typename T>
  void Put(const std::vector<T>& v) {
    Put(static_cast<uint64_t>(v.size()));
    for (const T& x : v) Put(x);
  }
  template <typename T>
  void Put(const std::optional<T>& v) {
    Put(static_cast<uint8_t>(v.has_value()));
    if (v) Put(*v);
  }
  void Put(const Contact& c);
  void Put(const PartMotion& m);
  void Put(const ContactReport& r);
  void Put(const MotionFailure& f);
  void Put(const PathTrial& t);  // all but its candidate (known to every process)
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> Get(T& v) {
    Need(sizeof v);
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
  }
  void Get(Vector3& v) {
    for (int k = 0; k < 3; ++k) Get(v[k]);
  }
  void Get(std::string& s) {
    uint64_t n = 0;
    Get(n);
    Need(n);
    s.assign(bytes_, at_, n);
    at_ += n;
  }
  template <typename T>
  void Get(std::vector<T>& v) {
    uint64_t n = 0;
    Get(n);
    Need(n);  // at least a byte each: a corrupt count fails here, not in resize
    v.resize(n);
    for (T& x : v) Get(x);
  }
  template <typename T>
  void Get(std::optional<T>& v) {
    uint8_t has = 0;
    Get(has);
    v.reset();
    if (has) Get(v.emplace());
  }
  void Get(Contact& c);
  void Get(PartMotion& m);
  void Get(ContactReport& r);
  void Get(MotionFailure& f);
  void Get(PathTrial& t);
  bool done() const { return at_ == bytes_.size(); }

 private:
  void Need(uint64_t n) const {
    CAIRN_THROW_UNLESS(n <= bytes_.size() - at_, "planner task result: truncated bytes");
  }
  const std::string& bytes_;
  size_t at_ = 0;
};

}  // namespace cairn::planning_codec
