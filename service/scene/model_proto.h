// Robot models <-> protobuf (service/proto/model.proto): a model
// description, which the journal keeps in place of its file, and the
// world's record of a loaded model, which snapshots keep. Both round trips
// are exact (doubles are copied, not printed).
#pragma once

#include "service/model/model_description.h"
#include "service/physics/model_record.h"
#include "service/physics/status.h"
#include "service/proto/model.pb.h"

namespace contactsim {

void SaveModelDescription(const model::ModelDescription& d, proto::ModelDescription* out);
// Errors name the link or joint whose field has the wrong size or value.
Status LoadModelDescription(const proto::ModelDescription& in, model::ModelDescription* d);

void SaveModelRecord(const ModelRecord& r, proto::ModelRecord* out);
Status LoadModelRecord(const proto::ModelRecord& in, ModelRecord* r);

}  // namespace contactsim
