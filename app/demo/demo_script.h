#pragma once
// Scripted input for the demo (`masav demo --script FILE`), how the tests drive the window under
// xvfb-run. One command per line, '#' starts a comment:
//   wait N                 draw N frames
//   set TABLE.KEY VALUE    change a parameter, as the panel does (e.g. set render.brightness 2)
//   view front|top|left|orbit
//   orbit YAW PITCH        orbit camera angles in degrees
//   scene PATH             switch to another scene file
//   backend NAME           switch the compute backend (vulkan, cuda, cpu)
//   pause | resume | step | reset | verify
//   panel on|off           expand or collapse the control panel
//   screenshot PATH        write the next frame (panel and overlay included) as PNG, and the
//                          layout beside it (PATH.layout: window, scene and panel rectangles)
//   key NAME               a keyboard shortcut (the names of shortcuts(): space, n, r, ...)
//   button NAME            a panel button (pause, step, reset, screenshot, record, save, panel)
//   rate R|off             simulated seconds per second of a stepped scene (SPH); off: the
//                          scene's own sph.substeps per frame
//   open PATH [dims=X,Y,Z] [type=T] [spacing=X,Y,Z] [big_endian] [array=NAME]
//                          open a volume file, as the panel's "Open" does (the options of
//                          `masav volume` for raw and .vti files)
//   tf load FILE | tf save FILE | tf reset | tf point V R G B A | tf delete V
//                          the transfer function editor (atom-volume and volume scenes): load or
//                          save a `--tf` file, the default back, set (or add) the point at value
//                          V, delete the point at V; as the panel's editor does (tf_points.h)
//   quit                   close the demo (also at the end of the script)
#include <string>
#include <vector>

namespace masav::app {

struct ScriptCommand {
  int line = 0;
  std::string verb;
  std::vector<std::string> args;
};

// Reads and checks the whole script up front: an unknown command or a wrong argument count is
// an error naming the file, the line and the allowed forms.
std::vector<ScriptCommand> load_script(const std::string& path);

}  // namespace masav::app
