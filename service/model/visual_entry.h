// A link's visual element between the description (model_description.h)
// and the world's model record (model_record.h), which keeps it for viewers
// without the mesh's vertices: the viewer loads the mesh file itself.
#pragma once

#include "service/model/model_description.h"
#include "service/physics/model_record.h"

namespace contactsim::model {

ModelVisualEntry ToVisualEntry(const VisualElement& v);
VisualElement FromVisualEntry(const ModelVisualEntry& e);

}  // namespace contactsim::model
