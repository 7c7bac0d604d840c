#include "service/model/visual_entry.h"

namespace contactsim::model {

ModelVisualEntry ToVisualEntry(const VisualElement& v) {
  ModelVisualEntry e;
  e.geometry = static_cast<int>(v.geometry.type);
  e.position = v.origin.position;
  e.orientation = v.origin.orientation;
  e.box_size = v.geometry.box_size;
  e.radius = v.geometry.radius;
  e.length = v.geometry.length;
  e.mesh_path = v.geometry.mesh_path;
  e.mesh_scale = v.geometry.mesh_scale;
  e.rgba = v.rgba;
  return e;
}

VisualElement FromVisualEntry(const ModelVisualEntry& e) {
  VisualElement v;
  v.geometry.type = static_cast<GeometryType>(e.geometry);
  v.origin = Pose{e.position, e.orientation};
  v.geometry.box_size = e.box_size;
  v.geometry.radius = e.radius;
  v.geometry.length = e.length;
  v.geometry.mesh_path = e.mesh_path;
  v.geometry.mesh_scale = e.mesh_scale;
  v.rgba = e.rgba;
  return v;
}

}  // namespace contactsim::model
