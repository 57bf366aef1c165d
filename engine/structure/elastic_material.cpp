#include "engine/structure/elastic_material.h"

#include "engine/structure/validation.h"

namespace pfem::structure {

ElasticMaterial::ElasticMaterial(double E) : E_(E) { require_positive(E, "e"); }

std::unique_ptr<UniaxialMaterial> ElasticMaterial::clone() const {
  return std::make_unique<ElasticMaterial>(*this);
}

void ElasticMaterial::archive(StateArchive& a) {
  UniaxialMaterial::archive(a);
  a(strain_), a(committed_strain_);
}

}  // namespace pfem::structure
