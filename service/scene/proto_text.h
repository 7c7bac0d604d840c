// Reads a protobuf text-format file; syntax errors come back as
// "FILE:LINE:COLUMN: message", and the parse-info tree lets callers point
// semantic errors at the line of the offending field.
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <string>

#include "service/physics/status.h"

namespace contactsim {

Status ReadTextProto(const std::string& path, google::protobuf::Message* message,
                     google::protobuf::TextFormat::ParseInfoTree* tree);

Status ParseTextProto(const std::string& text, const std::string& filename, google::protobuf::Message* message,
                      google::protobuf::TextFormat::ParseInfoTree* tree);

// "FILE:LINE" of a field (1-based line), or "FILE" when unknown.
std::string FieldLocation(const std::string& filename, const google::protobuf::TextFormat::ParseInfoTree* tree,
                          const google::protobuf::Message& message, const std::string& field, int index = -1);

}  // namespace contactsim
