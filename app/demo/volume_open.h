#pragma once
// Opening a volume file from the demo: the panel's path field and "Open" button, a file dropped
// on the window and the script's `open` all fill the same fields and make the same request. The
// demo then switches to a `volume` scene of the file (engine/volume/volume_scene.h), which reads it
// with the loader and the checks of `masav volume`; a file that is refused leaves the current
// scene, with the message in the panel.
#include <string>
#include <vector>

#include "registry/scene_file.h"

namespace masav::app {

// What the panel's fields hold: the [source] keys of the volume scene, as text.
struct OpenFields {
  std::string path;
  std::string dims;     // raw: X,Y,Z
  std::string type;     // raw: uint8, ..., float64
  std::string spacing;  // raw: X,Y,Z ('' = 1,1,1)
  bool big_endian = false;
  std::string array;  // vti
};

// The volume scene of the fields, at the defaults otherwise (not yet read: the scene reads the
// file when it is created).
scene::SceneFile volume_scene_file(const OpenFields& f);

// The script's `open PATH [dims=X,Y,Z] [type=T] [spacing=X,Y,Z] [big_endian] [array=NAME]`.
// An unknown word is an error naming it and `where` (the script's file and line).
OpenFields open_fields_from_words(const std::vector<std::string>& words, const std::string& where);

// The panel's "open a volume" section: path, the raw and vti options, the Open button. Sets
// `request` when the button is pressed or Enter is hit in the path field.
void volume_open_controls(OpenFields& fields, bool& request);

}  // namespace masav::app
