// Class tables of SemanticKITTI (semantic-kitti.yaml, `labels`) and RELLIS-3D (the dataset's
// ontology, as in its benchmarks' rellis.yaml), and RELLIS-3D's ground classes.
#include "host/eval/ontology.h"

#include <stdexcept>

namespace lpir {
namespace {

struct ClassEntry {
  uint32_t id;
  const char* name;
};

constexpr ClassEntry kSemanticKittiClasses[] = {
    {0, "unlabeled"},
    {1, "outlier"},
    {10, "car"},
    {11, "bicycle"},
    {13, "bus"},
    {15, "motorcycle"},
    {16, "on-rails"},
    {18, "truck"},
    {20, "other-vehicle"},
    {30, "person"},
    {31, "bicyclist"},
    {32, "motorcyclist"},
    {40, "road"},
    {44, "parking"},
    {48, "sidewalk"},
    {49, "other-ground"},
    {50, "building"},
    {51, "fence"},
    {52, "other-structure"},
    {60, "lane-marking"},
    {70, "vegetation"},
    {71, "trunk"},
    {72, "terrain"},
    {80, "pole"},
    {81, "traffic-sign"},
    {99, "other-object"},
    {252, "moving-car"},
    {253, "moving-bicyclist"},
    {254, "moving-person"},
    {255, "moving-motorcyclist"},
    {256, "moving-on-rails"},
    {257, "moving-bus"},
    {258, "moving-truck"},
    {259, "moving-other-vehicle"},
};

constexpr ClassEntry kRellis3dClasses[] = {
    {0, "void"},      {1, "dirt"},     {3, "grass"},   {4, "tree"},   {5, "pole"},
    {6, "water"},     {7, "sky"},      {8, "vehicle"}, {9, "object"}, {10, "asphalt"},
    {12, "building"}, {15, "log"},     {17, "person"}, {18, "fence"}, {19, "bush"},
    {23, "concrete"}, {27, "barrier"}, {31, "puddle"}, {33, "mud"},   {34, "rubble"},
};

template <size_t N>
const char* Find(const ClassEntry (&table)[N], uint32_t cls) {
  for (const ClassEntry& e : table)
    if (e.id == cls) return e.name;
  return "unknown";
}

}  // namespace

const char* OntologyName(Ontology ontology) {
  return ontology == Ontology::kRellis3d ? "rellis3d" : "semantickitti";
}

Ontology ParseOntology(const std::string& name) {
  for (Ontology o : {Ontology::kSemanticKitti, Ontology::kRellis3d})
    if (name == OntologyName(o)) return o;
  throw std::invalid_argument("unknown ontology '" + name + "' (known: semantickitti, rellis3d)");
}

const char* ClassName(Ontology ontology, uint32_t cls) {
  return ontology == Ontology::kRellis3d ? Find(kRellis3dClasses, cls)
                                         : Find(kSemanticKittiClasses, cls);
}

bool IsRellisGroundClass(uint32_t label) {
  switch (ClassOf(label)) {
    case 1:   // dirt
    case 3:   // grass
    case 6:   // water
    case 10:  // asphalt
    case 23:  // concrete
    case 31:  // puddle
    case 33:  // mud
      return true;
    default:
      return false;
  }
}

}  // namespace lpir
