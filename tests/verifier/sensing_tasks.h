// The hand-checked sensing-termination task (Buckley §3.1.2 type 2, §4.5) shared by the verifier and rollout
// tests: a 10 x 10 x 5 in C-space room, a damper that presses into the floor at 45 degrees and slides along
// +x through a position box.
#pragma once

#include <string>

namespace cmt::test {

// Room x, y in [-5, 5], z in [0, 5]; mu = .25 (phi = .2450), theta_v = .1, eps_s = .1. Start: the floor
// square x in [-4.5, -3.5], y in [-1, 1]. Damper v = (1, 0, -1)/sqrt 2: every velocity of cone(v, .1) is 45
// +- 5.7 degrees from -z, outside the floor's cone (.245 rad) and pressing, so the robot slides on the floor
// with azimuths within w = asin(sin .1 / sin 45deg) = .141658 rad of +x (Alg 4.3, tangent case) and never
// sticks there; the wall x = 5 is never-stick too (-v is 45 degrees from its normal -x), and the concave edge
// they share sticks (-v lies between the two normals). `terminate` is spliced in as the motion's termination
// sets.
inline std::string sensing_room(const std::string& terminate) {
  return "name: sensing_room\nunits: in\nfriction: 0.25\n"
         "uncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1}\n"
         "cspace: []\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\n"
         "start: {polygon: [[-4.5, -1, 0], [-3.5, -1, 0], [-3.5, 1, 0], [-4.5, 1, 0]]}\n"
         "goal: {segment: [[5, -5, 0], [5, 5, 0]]}\n"
         "motions:\n  m: {damper: [1, 0, -1]" +
         (terminate.empty() ? std::string() : ", terminate: " + terminate) + "}\nstrategies:\n  s: [m]\n";
}

}  // namespace cmt::test
