#include "experiments/sweep/spec/stable_hash.h"

#include <cstdint>

namespace cmt {

namespace {

using u128 = unsigned __int128;

constexpr u128 make_u128(std::uint64_t high, std::uint64_t low) {
  return (static_cast<u128>(high) << 64) | low;
}

// The FNV-1a 128-bit offset basis and prime (FNV specification).
constexpr u128 kFnvOffsetBasis = make_u128(0x6c62272e07bb0142ULL, 0x62b821756295c58dULL);
constexpr u128 kFnvPrime = (static_cast<u128>(1) << 88) | 0x13b;

}  // namespace

std::string fnv1a128_hex(std::string_view data) {
  u128 h = kFnvOffsetBasis;
  for (const char c : data) {
    h ^= static_cast<unsigned char>(c);
    h *= kFnvPrime;  // modulo 2^128 by unsigned wrap-around
  }
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex(32, '0');
  for (int i = 31; i >= 0; --i) {
    hex[i] = kDigits[static_cast<unsigned>(h & 0xf)];
    h >>= 4;
  }
  return hex;
}

HashInput& HashInput::add(std::string_view field) {
  text_ += std::to_string(field.size());
  text_ += ':';
  text_ += field;
  text_ += '\n';
  return *this;
}

HashInput& HashInput::add(long long value) { return add(std::to_string(value)); }

}  // namespace cmt
