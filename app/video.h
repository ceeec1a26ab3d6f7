#pragma once
// MP4 from numbered PNG frames (DIR/frame_00000.png, ...) through ffmpeg, for `masav run` and the
// demo's recorder.
#include <cstdint>
#include <string>

namespace masav::app {

// Encodes the frames into DIR/NAME.mp4 through a temporary file, renamed when complete, and says
// so on stdout. If ffmpeg fails, or runs past `limit_s` seconds (then it is killed), warns on
// stderr (the frames stay complete) and returns false.
bool write_video(const std::string& ffmpeg, const std::string& dir, const std::string& name,
                 double fps, double limit_s);
// The default limit for `frames` frames: 60 s plus half a second per frame.
double video_time_limit(uint64_t frames);

}  // namespace masav::app
