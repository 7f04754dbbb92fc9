// SameBits: two body states equal to the last bit (pose, velocities and
// the awake flag), for the tests that prove "unchanged" or "the same run".
#pragma once

#include <cstring>

#include "talus/body.h"

namespace talus::testing_support {

inline bool SameBits(const BodyState& a, const BodyState& b) {
  return std::memcmp(a.position.data(), b.position.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(), 4 * sizeof(double)) == 0 &&
         std::memcmp(a.linearVelocity.data(), b.linearVelocity.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.angularVelocity.data(), b.angularVelocity.data(), 3 * sizeof(double)) == 0 &&
         a.awake == b.awake;
}

}  // namespace talus::testing_support
