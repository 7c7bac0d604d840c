#include "service/scene/proto_text.h"

#include <google/protobuf/io/tokenizer.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace contactsim {
namespace {

class CollectFirstError : public google::protobuf::io::ErrorCollector {
 public:
  explicit CollectFirstError(std::string filename) : filename_(std::move(filename)) {}
  void AddError(int line, int column, const std::string& message) override {
    if (!first_.empty()) return;
    first_ = filename_ + ":" + std::to_string(line + 1) + ":" + std::to_string(column + 1) + ": " + message;
  }
  void AddWarning(int, int, const std::string&) override {}
  const std::string& first() const { return first_; }

 private:
  std::string filename_;
  std::string first_;
};

}  // namespace

Status ParseTextProto(const std::string& text, const std::string& filename, google::protobuf::Message* message,
                      google::protobuf::TextFormat::ParseInfoTree* tree) {
  CollectFirstError errors(filename);
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  if (tree != nullptr) parser.WriteLocationsTo(tree);
  if (!parser.ParseFromString(text, message)) {
    return Status::InvalidArgument(errors.first().empty() ? filename + ": cannot parse" : errors.first());
  }
  return Status::Ok();
}

Status ReadFileBounded(const std::string& path, std::string* bytes) {
  // a path comes from the network: a device or fifo could be read forever
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return Status::NotFound(path + ": cannot open file");
  if (!std::filesystem::is_regular_file(status)) return Status::InvalidArgument(path + ": not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return Status::NotFound(path + ": cannot open file");
  if (size > kMaxFileBytes) {
    return Status::ResourceExhausted(path + ": " + std::to_string(size) + " bytes, more than the " +
                                     std::to_string(kMaxFileBytes >> 20) + " MiB a scene or snapshot file may have");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::NotFound(path + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  *bytes = buffer.str();
  return Status::Ok();
}

Status ReadTextProto(const std::string& path, google::protobuf::Message* message,
                     google::protobuf::TextFormat::ParseInfoTree* tree) {
  std::string text;
  const Status st = ReadFileBounded(path, &text);
  if (!st.ok()) return st;
  return ParseTextProto(text, path, message, tree);
}

std::string FieldLocation(const std::string& filename, const google::protobuf::TextFormat::ParseInfoTree* tree,
                          const google::protobuf::Message& message, const std::string& field, int index) {
  if (tree == nullptr) return filename;
  const auto* fd = message.GetDescriptor()->FindFieldByName(field);
  if (fd == nullptr) return filename;
  const auto loc = tree->GetLocation(fd, index);
  if (loc.line < 0) return filename;
  return filename + ":" + std::to_string(loc.line + 1);
}

}  // namespace contactsim
