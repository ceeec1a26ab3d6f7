#pragma once
// The demo at rest: when nothing has changed for a few frames (no stage ran: a still volume, a
// paused simulation, a fixed camera) it waits for the window system's next event, or at most a
// quarter second, instead of drawing the same frame as fast as it can. Any input wakes it at
// once. A script, a recording and queued actions keep it drawing every frame.
#include <cstdint>

namespace masav::app {

// Frames with no stage run before the demo starts to wait, and the longest wait.
constexpr uint32_t kIdleFramesBeforeWait = 3;
constexpr double kIdleWaitSeconds = 0.25;

struct IdleInputs {
  uint32_t quiet_frames = 0;  // consecutive frames whose update ran no stage
  bool scripted = false;      // a --script drives the demo (its waits count frames)
  bool recording = false;
  bool actions_queued = false;
};

// The longest the coming frame may wait for an event, in seconds (0: poll and draw at once).
double idle_wait_seconds(const IdleInputs& in);

}  // namespace masav::app
