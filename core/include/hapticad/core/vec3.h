// SPDX-License-Identifier: GPL-3.0-or-later
// The one vector type of the core: a double-precision 3-vector.
//
// Doubles everywhere: a float at 1000 units has a 6.1e-5 step, coarser than the
// depth a haptic proxy resolves. Frames are named in identifiers: `_w` is the world
// (CAD model) frame in metres, `_l` the scene's local frame (world minus the scene's
// origin, metres). Fixed-size Eigen types never allocate.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross()

namespace hapticad {

using Vec3 = Eigen::Vector3d;

}  // namespace hapticad
