#pragma once
// The checks of each section of a pfem.v1.Model, in the files check_*.cpp; ModelChecker::run()
// calls them in turn, each adding what it finds to the one FieldChecker (internal to engine/io/).
#include "engine/io/field_checker.h"
#include "engine/io/structure_names.h"
#include "pfem/v1/model.pb.h"

namespace pfem {

// check_fluid_mesh.cpp: the fluid, the mesh and the analysis settings.
void check_fluid(const pfem::v1::Model& model, FieldChecker& out);
void check_mesh(const pfem::v1::Model& model, FieldChecker& out);
void check_analysis(const pfem::v1::Model& model, FieldChecker& out);

// check_walls_regions.cpp: the geometry (walls, domain, fluid regions).
void check_walls(const pfem::v1::Model& model, FieldChecker& out);
void check_domain(const pfem::v1::Model& model, FieldChecker& out);
void check_regions(const pfem::v1::Model& model, FieldChecker& out);

// check_recorders.cpp, check_parameters.cpp, check_structure.cpp.
void check_recorders(const pfem::v1::Model& model, const StructureNames& components, FieldChecker& out);
void check_parameters(const pfem::v1::Model& model, FieldChecker& out);
void check_structure(const pfem::v1::Model& model, const StructureNames& names, FieldChecker& out);

}  // namespace pfem
