#pragma once
// MP4 from numbered PNG frames (DIR/frame_00000.png, ...) through ffmpeg, for `masav run` and the
// demo's recorder.
#include <string>

namespace masav::app {

// Encodes the frames into DIR/NAME.mp4 through a temporary file, renamed when complete, and says
// so on stdout. If ffmpeg fails, warns on stderr (the frames stay complete) and returns false.
bool write_video(const std::string& ffmpeg, const std::string& dir, const std::string& name,
                 double fps);

}  // namespace masav::app
