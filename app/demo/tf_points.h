#pragma once
// The demo's transfer function editor without ImGui: the edits of its control points (add, move,
// recolour, delete), which keep the points a valid transfer function (values strictly ascending
// in [0, 1], every number in [0, 1], at least kMinTfPoints), and the link to the scene's keys.
// The editor (tf_editor.cpp) and the script's `tf` verbs both edit through these.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/volume/transfer_function.h"

namespace masav::app {

using volume::TransferPoint;

// Fewer than two points would make the function one constant colour, which the editor's
// value axis could no longer change.
constexpr size_t kMinTfPoints = 2;
// The smallest distance between two points' values: the format wants them strictly ascending.
constexpr double kMinTfGap = 1e-3;

// Adds a point at `value` (clamped to [0, 1]) with the colour and opacity the function has there,
// so that the function is unchanged until the point is edited. Returns its index; none when a
// point is closer than kMinTfGap (the caller selects that one instead).
std::optional<size_t> add_tf_point(std::vector<TransferPoint>& pts, double value);
// Moves point `i` to `value` and `opacity`: the value clamped between its neighbours' (kMinTfGap
// away) and to [0, 1], so the order never changes; the opacity clamped to [0, 1].
void move_tf_point(std::vector<TransferPoint>& pts, size_t i, double value, double opacity);
// Sets point `i`'s colour and opacity, each clamped to [0, 1].
void set_tf_colour(std::vector<TransferPoint>& pts, size_t i, double r, double g, double b,
                   double a);
// Deletes point `i`; false (nothing deleted) when only kMinTfPoints are left.
bool delete_tf_point(std::vector<TransferPoint>& pts, size_t i);
// The index of the point within `tolerance` of `value`, the nearest one; none if there is none.
std::optional<size_t> tf_point_near(const std::vector<TransferPoint>& pts, double value,
                                    double tolerance);
// Sets the point at `value` (within kMinTfGap) to the colour, or adds one there: the script's
// `tf point V R G B A`. Every number must be in [0, 1]; errors name `where` and the field.
void put_tf_point(std::vector<TransferPoint>& pts, const std::vector<std::string>& numbers,
                  const std::string& where);

// What the editor holds between frames.
struct TfEditorState {
  std::vector<TransferPoint> points;  // as the scene's keys give them (see sync_tf_editor)
  std::optional<size_t> selected, dragging;
  std::string keys;              // the table and its two keys' text the points were read from
  std::vector<float> histogram;  // log heights (value_histogram.h)
  uint64_t histogram_version = 0;
  std::string path = "transfer.txt";  // of "Save TF..." and "Load TF..."
  std::string message;                // the last refusal, or what was saved or loaded
  bool message_is_error = false;
};

// Reads the points from `table`'s keys when they changed since the last call (a script's `set`,
// a loaded scene), so the editor always shows what the scene renders. A file that cannot be read
// leaves the default points and the reason in `message`.
void sync_tf_editor(TfEditorState& e, const scene::ParamSet& p, const std::string& table);

// The table whose `transfer` and `transfer_file` keys hold the scene's transfer function
// ("volume" in atom-volume, "raymarch" in a volume file's scene); none for other scenes.
std::optional<std::string> transfer_table(const scene::ParamSet& p);
// Stores `pts` in the scene as its inline points (`table`.transfer), clearing the file key: only
// the transfer function's stages rerun. Throws masav::Error (the scene keeps its old points).
void apply_tf_points(scene::SceneInstance& s, const std::string& table,
                     const std::vector<TransferPoint>& pts);
// The default points back: both keys cleared.
void reset_tf_points(scene::SceneInstance& s, const std::string& table);

// "Save TF...": writes the editor's points to `path` in the `--tf` format; "Load TF...": reads
// a file with the checks of `--tf` and applies its points. Both report in e.message (a refusal
// names the file, the line and the field) and never throw.
void save_tf_file(TfEditorState& e, const std::string& path);
void load_tf_file(TfEditorState& e, scene::SceneInstance& s, const std::string& table,
                  const std::string& path);
// A new scene (or the same on another backend): points and histogram are read afresh; the file
// field keeps its path.
void forget_tf_scene(TfEditorState& e);

// The script's `tf` verbs, as the editor's controls do them:
//   tf load FILE | tf save FILE | tf reset | tf point V R G B A | tf delete V
// Word counts and numbers are checked by check_tf_words (when the script is read); `run_tf_words`
// throws masav::Error naming `where` when the scene has no transfer function or a number is out
// of range, and returns what the editor's message says after the command.
void check_tf_words(const std::vector<std::string>& words, const std::string& where);
std::string run_tf_words(TfEditorState& e, scene::SceneInstance& s,
                         const std::vector<std::string>& words, const std::string& where);

}  // namespace masav::app
