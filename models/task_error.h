// The error of a bad task file (docs/task-format.md "Validation"): the file, the YAML key path and the
// reason, and for a YAML syntax error where in the text it is. An InputError (models/input_error.h), so that
// one handler reports every bad input.
#pragma once

#include "models/input_error.h"

namespace cmt {

class TaskError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace cmt
