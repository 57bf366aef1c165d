#include "engine/structure/uniaxial_material.h"

namespace pfem::structure {

void UniaxialMaterial::set_num_parameters(int P) { total_.assign(P, Total{}); }

void UniaxialMaterial::set_strain_sensitivity(int k, double dstrain) {
  total_.at(k) = {dstrain, tangent() * dstrain + conditional_stress_sensitivity(k)};
  update_history_sensitivity(k, dstrain);
}

void UniaxialMaterial::archive(StateArchive& a) {
  a.expect(total_.size(), "parameters of a material");
  for (auto& t : total_) a(t.strain), a(t.stress);
}

}  // namespace pfem::structure
