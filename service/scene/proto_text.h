// Reads a protobuf text-format file; syntax errors come back as
// "FILE:LINE:COLUMN: message", and the parse-info tree lets callers point
// semantic errors at the line of the offending field.
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <cstdint>
#include <string>

#include "service/physics/status.h"

namespace contactsim {

// Scene and snapshot files are at most this large.
constexpr uint64_t kMaxFileBytes = uint64_t{256} << 20;

// Reads a whole regular file of at most kMaxFileBytes; paths come from the
// network, so devices, fifos and folders are refused instead of read.
Status ReadFileBounded(const std::string& path, std::string* bytes);

Status ReadTextProto(const std::string& path, google::protobuf::Message* message,
                     google::protobuf::TextFormat::ParseInfoTree* tree);

Status ParseTextProto(const std::string& text, const std::string& filename, google::protobuf::Message* message,
                      google::protobuf::TextFormat::ParseInfoTree* tree);

// "FILE:LINE" of a field (1-based line), or "FILE" when unknown.
std::string FieldLocation(const std::string& filename, const google::protobuf::TextFormat::ParseInfoTree* tree,
                          const google::protobuf::Message& message, const std::string& field, int index = -1);

}  // namespace contactsim
