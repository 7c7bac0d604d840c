#include "service/server/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "service/scene/snapshot.h"

namespace contactsim {
namespace fs = std::filesystem;
namespace {

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as zlib's crc32.
uint32_t Crc32(const char* data, size_t n) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i < n; ++i) c = table[(c ^ static_cast<uint8_t>(data[i])) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

template <typename T>
void Put(std::string* out, T v) {
  out->append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <typename T>
T Get(const std::string& bytes, size_t at) {
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

constexpr size_t kHeaderBytes = 4 + 1 + 8 + 8;

std::string Numbered(const std::string& dir, const char* stem, int64_t n, const char* ext) {
  char name[64];
  std::snprintf(name, sizeof name, "%s-%012lld%s", stem, static_cast<long long>(n), ext);
  return dir + "/" + name;
}

// Files "<stem>-<number><ext>" in dir, ascending by number.
std::vector<std::pair<int64_t, std::string>> ListNumbered(const std::string& dir, const std::string& stem,
                                                          const std::string& ext) {
  std::vector<std::pair<int64_t, std::string>> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= stem.size() + 1 + ext.size() || name.compare(0, stem.size() + 1, stem + "-") != 0 ||
        name.compare(name.size() - ext.size(), ext.size(), ext) != 0) {
      continue;
    }
    const std::string digits = name.substr(stem.size() + 1, name.size() - stem.size() - 1 - ext.size());
    if (digits.empty() || !std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    out.emplace_back(std::stoll(digits), entry.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

void SyncDir(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

Status ParseFsyncPolicy(const std::string& text, FsyncPolicy* policy) {
  if (text == "always") *policy = FsyncPolicy::kAlways;
  else if (text == "none") *policy = FsyncPolicy::kNone;
  else return Status::InvalidArgument("journal_fsync must be \"always\" or \"none\", got \"" + text + "\"");
  return Status::Ok();
}

void EncodeRecord(const JournalRecord& r, std::string* out) {
  const size_t start = out->size();
  Put<uint32_t>(out, static_cast<uint32_t>(r.payload.size()));
  Put<uint8_t>(out, static_cast<uint8_t>(r.kind));
  Put<int64_t>(out, r.seq);
  Put<int64_t>(out, r.step);
  out->append(r.payload);
  Put<uint32_t>(out, Crc32(out->data() + start + 4, out->size() - start - 4));
}

bool DecodeRecord(const std::string& bytes, size_t* offset, JournalRecord* r) {
  const size_t at = *offset;
  if (bytes.size() - at < kHeaderBytes + 4) return false;
  const uint32_t n = Get<uint32_t>(bytes, at);
  if (n > kMaxJournalPayload || bytes.size() - at < kHeaderBytes + n + 4) return false;
  if (Crc32(bytes.data() + at + 4, kHeaderBytes - 4 + n) != Get<uint32_t>(bytes, at + kHeaderBytes + n)) return false;
  const uint8_t kind = Get<uint8_t>(bytes, at + 4);
  // 7: queries are never written
  if (kind < 1 || kind > static_cast<uint8_t>(RecordKind::kWsgCommand) || kind == 7) return false;
  r->kind = static_cast<RecordKind>(kind);
  r->seq = Get<int64_t>(bytes, at + 5);
  r->step = Get<int64_t>(bytes, at + 13);
  r->payload.assign(bytes, at + kHeaderBytes, n);
  *offset = at + kHeaderBytes + n + 4;
  return true;
}

Journal::~Journal() { Close(); }

void Journal::Close() {
  if (fd_ >= 0) {
    if (policy_ == FsyncPolicy::kAlways) ::fdatasync(fd_);
    ::close(fd_);
    fd_ = -1;
  }
}

Status Journal::Open(const std::string& dir, FsyncPolicy policy) {
  Close();
  dir_ = dir;
  policy_ = policy;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) return Status::FailedPrecondition("cannot create journal folder " + dir);

  // the latest readable snapshot (an unreadable one was cut short by a crash
  // before its rename: it cannot be, but be lenient)
  recovered_snapshot_.reset();
  auto snapshots = ListNumbered(dir, "snapshot", ".pb");
  for (auto it = snapshots.rbegin(); it != snapshots.rend(); ++it) {
    proto::Snapshot s;
    if (ReadSnapshotFile(it->second, &s).ok()) {
      recovered_snapshot_ = std::move(s);
      break;
    }
  }
  const int64_t from = recovered_snapshot_ ? recovered_snapshot_->journal_seq() : 0;
  next_seq_ = from;

  recovered_records_.clear();
  bool torn = false;
  for (const auto& [start, path] : ListNumbered(dir, "journal", ".bin")) {
    if (torn) {  // nothing after a torn record can be trusted
      fs::remove(path, ec);
      continue;
    }
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const std::string bytes = text.str();
    size_t offset = 0;
    JournalRecord r;
    while (offset < bytes.size()) {
      const size_t before = offset;
      if (!DecodeRecord(bytes, &offset, &r) || (r.seq >= from && r.seq != next_seq_)) {
        fs::resize_file(path, before, ec);
        torn = true;
        break;
      }
      if (r.seq >= from) {
        recovered_records_.push_back(r);
        next_seq_ = r.seq + 1;
      }
    }
  }
  return OpenSegment();
}

void Journal::DropRecovered() {
  recovered_snapshot_.reset();
  recovered_records_.clear();
  recovered_records_.shrink_to_fit();
}

Status Journal::OpenSegment() {
  Close();
  segment_start_ = next_seq_;
  const std::string path = Numbered(dir_, "journal", segment_start_, ".bin");
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) return Status::Internal("cannot open journal segment " + path + ": " + std::strerror(errno));
  segment_bytes_ = ::lseek(fd_, 0, SEEK_END);
  if (policy_ == FsyncPolicy::kAlways) SyncDir(dir_);
  return Status::Ok();
}

// Records go to the kernel at once (write(2), no stdio buffer), so a full
// or failing disk shows here, before the command is acknowledged.
Status Journal::Append(RecordKind kind, int64_t step, const std::string& payload, JournalRecord* out) {
  if (failed_) return Status::Internal("the journal in " + dir_ + " failed earlier and takes no more records");
  if (payload.size() > kMaxJournalPayload) {
    return Status::ResourceExhausted("a journal record holds at most " + std::to_string(kMaxJournalPayload) +
                                     " bytes, got " + std::to_string(payload.size()));
  }
  JournalRecord r;
  r.seq = next_seq_;
  r.step = step;
  r.kind = kind;
  r.payload = payload;
  if (open()) {
    std::string bytes;
    EncodeRecord(r, &bytes);
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const std::string why = n < 0 ? std::strerror(errno) : "short write";
        // cut the partial record off so that the segment stays readable
        if (::ftruncate(fd_, segment_bytes_) != 0) failed_ = true;
        return Status::Internal("cannot append to the journal in " + dir_ + ": " + why);
      }
      done += static_cast<size_t>(n);
    }
    segment_bytes_ += static_cast<int64_t>(bytes.size());
    dirty_ = true;
  }
  ++next_seq_;
  if (out != nullptr) *out = std::move(r);
  return Status::Ok();
}

Status Journal::Sync() {
  if (!open() || !dirty_) return Status::Ok();
  dirty_ = false;
  // write(2) already handed the records to the kernel (enough to survive a
  // killed server); fdatasync puts them on the disk
  if (policy_ == FsyncPolicy::kAlways && ::fdatasync(fd_) != 0) {
    return Status::Internal("cannot sync the journal in " + dir_ + ": " + std::strerror(errno));
  }
  return Status::Ok();
}

Status Journal::RollBack(const Mark& mark) {
  next_seq_ = mark.seq;
  dirty_ = false;
  if (!open() || mark.segment_start != segment_start_) return Status::Ok();
  if (::ftruncate(fd_, mark.bytes) != 0 || (policy_ == FsyncPolicy::kAlways && ::fdatasync(fd_) != 0)) {
    failed_ = true;
    return Status::Internal("cannot cut the journal in " + dir_ + " back to record " + std::to_string(mark.seq) +
                            ": " + std::strerror(errno) + "; the journal takes no more records until restart");
  }
  segment_bytes_ = mark.bytes;
  return Status::Ok();
}

Status Journal::WriteSnapshot(proto::Snapshot snapshot) {
  if (!open()) return Status::FailedPrecondition("no journal folder configured");
  Status st = Sync();
  if (!st.ok()) return st;
  snapshot.set_journal_seq(next_seq_);
  const std::string path = Numbered(dir_, "snapshot", next_seq_, ".pb");
  if (!(st = WriteSnapshotFile(path, snapshot, policy_ == FsyncPolicy::kAlways)).ok()) return st;
  // the new snapshot is durable: what came before it is no longer needed
  std::error_code ec;
  for (const auto& [seq, old] : ListNumbered(dir_, "snapshot", ".pb")) {
    if (seq < next_seq_) fs::remove(old, ec);
  }
  if (segment_start_ != next_seq_) {
    if (!(st = OpenSegment()).ok()) return st;
  }
  for (const auto& [start, old] : ListNumbered(dir_, "journal", ".bin")) {
    if (start < next_seq_) fs::remove(old, ec);
  }
  return Status::Ok();
}

}  // namespace contactsim
