#pragma once
// pfem.v1.Wall.motion -> motion::WallMotion: the wavemakers of a validated model.
#include <vector>

#include "engine/io/model_io.h"
#include "engine/io/parameter_targets.h"
#include "engine/motion/wall_motion.h"

namespace pfem {

// The motion of one wall (wall.motion validated; its nodes and seeds left empty). gravity: |g|.
motion::WallMotion wall_motion(const pfem::v1::Wall& wall, double gravity);
double gravity_magnitude(const pfem::v1::Model& model);

// The moving walls of `model` (its parameters' values already applied), in wall order, each with
// its nodes (wall_nodes[w]: the nodes of wall w) and per DDM parameter k its seed, seeds[k].walls[w]
// (parameter_seeds of this model).
std::vector<motion::WallMotion> build_wall_motions(const pfem::v1::Model& model,
                                                   const std::vector<std::vector<int>>& wall_nodes,
                                                   const std::vector<ParameterSeed>& seeds);

}  // namespace pfem
