// Names of the stick/slide classes (stick_class.h), as the JSON outputs spell them.
#include "verifier/stick_class.h"

namespace cmt {

const char* stick_class_name(StickClass c) {
  switch (c) {
    case StickClass::kMust:
      return "must";
    case StickClass::kMay:
      return "may";
    case StickClass::kNever:
      return "never";
  }
  return "may";
}

}  // namespace cmt
