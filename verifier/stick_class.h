// The stick/slide class of an atom under one commanded motion (Buckley §4.2, §6.7.4): whether every
// admissible command sticks there (must), some may (may), or none does (never). Shared by the damper
// (damper.h classify_damper) and the spring (spring.h classify_spring).
#pragma once

namespace cmt {

enum class StickClass { kMust, kMay, kNever };
const char* stick_class_name(StickClass c);

}  // namespace cmt
