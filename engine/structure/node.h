#pragma once
// A node of the 2D frame: reference position, supports, lumped nodal mass and nodal load.
#include <array>

#include "engine/structure/types.h"

namespace pfem::structure {

struct Node {
  Vec2 x = Vec2::Zero();        // reference coordinates
  std::array<bool, 3> fixed{};  // supported dofs (ux, uy, rz): u = 0 there
  Vec3 mass = Vec3::Zero();     // nodal mass (mx, my, rotational inertia)
  Vec3 load = Vec3::Zero();     // external nodal load (Fx, Fy, Mz)
};

}  // namespace pfem::structure
