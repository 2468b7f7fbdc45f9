// The label sets evaluate reads: SemanticKITTI and RELLIS-3D. Both store a uint32 per point whose
// low 16 bits are the class id (SemanticKITTI keeps an instance id above them; RELLIS-3D 0).
#pragma once
#include <cstdint>
#include <string>

namespace lpir {

enum class Ontology {
  kSemanticKitti,  // semantic-kitti.yaml: 0 unlabeled ... 259 moving-other-vehicle
  kRellis3d,       // RELLIS-3D ontology: 0 void ... 34 rubble
};

// "semantickitti", "rellis3d".
const char* OntologyName(Ontology ontology);
// Inverse of OntologyName (case-sensitive); std::invalid_argument naming the valid ones.
Ontology ParseOntology(const std::string& name);

// The class id of a stored label: label & 0xFFFF.
inline uint32_t ClassOf(uint32_t label) { return label & 0xFFFFu; }

// The class's name in the dataset's own table ("road", "grass"); "unknown" for an id the
// ontology does not define. `cls` is a class id (ClassOf), not a raw label.
const char* ClassName(Ontology ontology, uint32_t cls);

// RELLIS-3D ground: 1 dirt, 3 grass, 6 water, 10 asphalt, 23 concrete, 31 puddle, 33 mud (on
// label & 0xFFFF). Void (0) is neither ground nor non-ground: the rellis protocol skips it.
bool IsRellisGroundClass(uint32_t label);
constexpr uint32_t kRellisVoid = 0;

}  // namespace lpir
