#include "app/demo/idle_wait.h"

namespace masav::app {

double idle_wait_seconds(const IdleInputs& in) {
  if (in.scripted || in.recording || in.actions_queued) return 0;
  return in.quiet_frames >= kIdleFramesBeforeWait ? kIdleWaitSeconds : 0;
}

}  // namespace masav::app
