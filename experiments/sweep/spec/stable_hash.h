// A hash that never changes between builds, compilers or machines (std::hash may): it names sweep units in
// results databases (experiments/sweep/spec/sweep_spec.h unit_key), so a rerun recognises finished work.
#pragma once

#include <string>
#include <string_view>

namespace cmt {

// FNV-1a with the 128-bit parameters of the FNV specification (Fowler, Noll, Vo; IETF draft
// draft-eastlake-fnv): offset basis 0x6c62272e07bb014262b821756295c58d, prime 2^88 + 2^8 + 0x3b. Not
// cryptographic; collisions between the (at most millions of) honest units of a sweep have probability
// below 1e-26. Returns 32 lower-case hex digits.
std::string fnv1a128_hex(std::string_view data);

// Builds the hashed text from fields without ambiguity: each field is written as its length, ':', the bytes
// and '\n', so ("ab", "c") and ("a", "bc") differ.
class HashInput {
 public:
  HashInput& add(std::string_view field);
  HashInput& add(long long value);
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

}  // namespace cmt
