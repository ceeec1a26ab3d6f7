#pragma once
// The checks of a state an SPH simulation is to continue from (SphResumeState), whoever hands it
// in: the checkpoint reader (sph_checkpoint.h) and SphSimulation::restore_resume_state, so a
// state that only passed its file's checksums, or one built by a program, is refused the way a
// bad flag or scene key is. A checksum proves the bytes are the ones written, not that they
// make a run: a NaN time never reaches any end time, a step count near 2^64 wraps the end step.
//
// Every field is checked against what the scene allows (its dt bounds, its box, its particle
// count, its pressure model) and against the other fields it must agree with (the counters, the
// watchdog's last good state); the first bad one throws masav::Error naming the field, the value
// and the allowed range. What is checked is listed in docs/sph.md ("Checkpoints").
#include "engine/sph/sph_params.h"
#include "engine/sph/sph_resume_state.h"

namespace masav {

// Positions may lie this many support radii h outside the box with walls on (the walls put a
// particle back on them at each step's end; the slack is for a backend's float rounding and
// stays far below any real escape). Walls off: any finite position.
inline constexpr double kResumeBoxSlackH = 1.0;

// Throws masav::Error (where "sph resume state") naming the first field of `r` that `scene`
// (valid: validate() is run first) cannot have continued from.
void validate_resume_state(const SphScene& scene, const SphResumeState& r);

}  // namespace masav
