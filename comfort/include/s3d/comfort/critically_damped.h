#pragma once
// A critically damped follower solved exactly over each frame (stable for any frame time), shared by the
// zero-parallax control and the disparity budget controller: it never passes its goal and never moves by
// more than the given bound in one step.
#include <algorithm>
#include <cmath>

namespace s3d::comfort {

struct CriticallyDamped {
  float value = 0.0f;
  float velocity = 0.0f;  // per second

  // Advances `seconds` toward `goal` with time constant `responseSeconds`; |change| <= maxChange. Returns value.
  float step(float goal, float seconds, float responseSeconds, float maxChange) {
    const float omega = 2.0f / responseSeconds;
    const float offset = value - goal;
    const float decay = std::exp(-omega * seconds);
    const float blend = (velocity + omega * offset) * seconds;
    float next = goal + (offset + blend) * decay;
    velocity = (velocity - omega * blend) * decay;
    // Never past the goal (a moving goal can leave velocity that would overshoot), never faster than the bound.
    if ((value - goal) * (next - goal) < 0.0f) {
      next = goal;
      velocity = 0.0f;
    }
    const float change = std::clamp(next - value, -maxChange, maxChange);
    if (change != next - value) velocity = change / seconds;
    value += change;
    return value;
  }

  // Jumps to `to` with no velocity left (a hard rule or a reset); the next step continues smoothly from there.
  void hold(float to) {
    value = to;
    velocity = 0.0f;
  }
};

}  // namespace s3d::comfort
