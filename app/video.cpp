#include "app/video.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "engine/util/output_file.h"
#include "app/interrupt.h"
#include "app/subprocess.h"

namespace masav::app {

double video_time_limit(uint64_t frames) {
  // Generous for libx264 on a slow CPU (it encodes hundreds of small frames per second).
  return 60.0 + 0.5 * double(frames);
}

bool write_video(const std::string& ffmpeg, const std::string& dir, const std::string& name,
                 double fps, double limit_s) {
  const std::string tmp = fmt::format("{}/.{}.tmp.mp4", dir, name);
  const std::string out = fmt::format("{}/{}.mp4", dir, name);
  // Even sizes for yuv420p; quiet unless it fails. No shell: the paths are arguments as they are.
  const ProcessResult rc = run_process(
      {ffmpeg, "-y", "-loglevel", "error", "-nostdin", "-framerate", fmt::format("{}", fps), "-i",
       dir + "/frame_%05d.png", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
       "-pix_fmt", "yuv420p", "-f", "mp4", tmp},
      limit_s, [] { return interrupted(); });
  std::error_code ec;
  if (!rc.started || rc.timed_out || rc.stopped || rc.signal || rc.exit_code != 0) {
    std::filesystem::remove(tmp, ec);
    fmt::print(stderr,
               "masav: warning: ffmpeg could not encode the video ({}); the PNG "
               "frames are complete\n",
               rc.describe(limit_s));
    return false;
  }
  // The video's name resolved as every output's (engine/util/output_file.h): a link replaced
  // through to its file, never renamed over.
  const OutputTarget target = resolve_output(out, "--out");
  if (target.in_place) {
    std::ifstream in(tmp, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(tmp, ec);
    write_output(out, bytes, "--out");
  } else {
    std::filesystem::rename(tmp, target.path, ec);
  }
  if (ec && !target.in_place) {
    std::filesystem::remove(tmp, ec);
    throw Error("", "--out", fmt::format("cannot rename the video onto '{}'", out),
                "choose a writable output directory");
  }
  fmt::print("wrote {}\n", out);
  return true;
}

}  // namespace masav::app
