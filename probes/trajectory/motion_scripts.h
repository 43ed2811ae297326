#pragma once
// The four scripted motions of probe_sim (see motion_params.h for what each
// parameter means per script). Each script starts with a hold in free space,
// repeats whole cycles while they fit in the duration, and holds at its
// start height for the remaining time.
//   approach_and_press: down from centre + amplitude*z to centre - depth*z,
//                       hold, back up; repeated.
//   slide:              down at centre - amplitude*direction, strokes to
//                       centre + amplitude*direction and back at depth, up.
//   stir:               down the cup axis to centre - depth*z, out to the
//                       circle radius (amplitude), circles, back, up.
//   insert_peg:         down the hole axis to centre - depth*z, optional
//                       circular wiggle of radius amplitude, hold, out;
//                       repeated.
#include "probes/trajectory/motion_params.h"
#include "probes/trajectory/motion_path.h"
#include "probes/trajectory/pose_sample.h"

namespace probes {

// Throws InputError if not even one cycle fits in params.duration.
MotionPath BuildMotionPath(const MotionParams& params);

// Samples the path at params.rate_hz from t = 0 for params.duration
// (floor(duration * rate) samples) with analytic velocities.
Trajectory SampleMotion(const MotionParams& params);

}  // namespace probes
