// Small inline tasks shared by the models tests.
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace cmt::test {

// `text` with the first `from` replaced by `to`; a test-setup failure when `from` is not there.
inline std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in the base task";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The inside of a 2 in cube (Buckley §6.3.1) as bounds only.
inline const std::string kCubeYaml = R"(
name: cube
units: in
friction: 0.25
uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: 0.25, theta_f: 0.3}
cspace: []
bounds: {min: [-1, -1, -1], max: [1, 1, 1]}
start: {segment: [[-1, -1, 1], [1, -1, 1]]}
goal: {polygon: [[-0.5, -0.5, -1], [0.5, -0.5, -1], [0.5, 0.5, -1], [-0.5, 0.5, -1]]}
motions:
  p1: {spring: [0, 0, -1.4]}
strategies:
  stick: [p1]
)";

// The C-space hole of Buckley §5.2 / §6.3.3: 2 wide, 2 deep, closed by the bounds box.
inline const std::string kHoleYaml = R"(
name: hole
units: in
friction: 0.48
uncertainty: {eps_s: 0.2, eps_p: 0.2, theta_v: 0.25, theta_f: 0.05}
cspace:
  - box: {min: [-6, -6, -2], max: [-1, 6, 0]}
  - box: {min: [1, -6, -2], max: [6, 6, 0]}
  - box: {min: [-1, -6, -2], max: [1, -1, 0]}
  - box: {min: [-1, 1, -2], max: [1, 6, 0]}
bounds: {min: [-6, -6, -2], max: [6, 6, 4]}
start: {segment: [[-4, -3, 0], [-2, -3, 0]]}
goal: {polygon: [[-1, -1, -2], [1, -1, -2], [1, 1, -2], [-1, 1, -2]]}
motions:
  p1: {spring: [0, 0, -2.4]}
  p2: {spring: [1.4, 0, -1]}
strategies:
  teach: [p2, p1]
)";

}  // namespace cmt::test
