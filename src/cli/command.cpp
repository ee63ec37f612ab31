#include "cli/command.h"

#include <exception>
#include <new>
#include <ostream>

#include "cairn/core/error.h"

namespace cairn::cli {

int RunGuarded(std::ostream& err, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    err << "cairn: internal error: out of memory\n";
    return kExitInternalError;
  } catch (const std::exception& e) {
    err << "cairn: internal error: " << e.what() << '\n';
    return kExitInternalError;
  } catch (...) {
    err << "cairn: internal error: an unknown exception\n";
    return kExitInternalError;
  }
}

}  // namespace cairn::cli
