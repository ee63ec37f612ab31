#pragma once
// A motion failure in a test's message: verdict, where and the part indices,
// without the report stage's words (the stages' tests do not link report).
#include <sstream>
#include <string>

#include "cairn/motion/simulate.h"

namespace cairn::testing {

inline std::string Brief(const MotionFailure& f) {
  std::ostringstream os;
  os << to_string(f.verdict) << " at step " << f.step << ", tick " << f.tick << " (t = " << f.time
     << " s), parts";
  for (int p : f.parts) os << ' ' << p;
  if (!f.solver_note.empty()) os << "; " << f.solver_note;
  return os.str();
}

}  // namespace cairn::testing
