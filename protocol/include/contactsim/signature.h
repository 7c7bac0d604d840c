// Signed LCM messages (docs/protocol.md, "Authentication"): the ordinary LCM
// encoding followed by a 44-byte trailer
//
//   payload | "CSG1" | seq (u64, little-endian) | mac (32 bytes)
//   mac = HMAC-SHA256(key, channel || 0x00 || payload || "CSG1" || seq_le)
//
// seq is the sender's wall clock in ns since the Unix epoch, made strictly
// increasing per sender, so that a receiver refuses old (stale) and repeated
// (replayed) messages without any state shared between the two. LCM's
// decoders read only the payload, so the stock LCM tools keep working.
//
// Used by the client (signs commands, verifies the server's output) and by
// the server (service/server/command_auth.h, signing_transport.h); nothing
// here throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <mutex>
#include <string>
#include <unordered_map>

namespace contactsim {

inline constexpr char kSignatureMagic[] = "CSG1";  // 4 bytes on the wire, no NUL
inline constexpr int kSignatureMagicBytes = 4;
inline constexpr int kSignatureMacBytes = 32;  // HMAC-SHA256
inline constexpr int kSignatureTrailerBytes = kSignatureMagicBytes + 8 + kSignatureMacBytes;  // 44
inline constexpr size_t kMinAuthKeyBytes = 32;
inline constexpr double kDefaultAuthWindowSeconds = 30.0;  // |seq - now| allowed
// Messages a receiver accepts out of order below the newest seq of a sender.
inline constexpr int kReplayWindowSlots = 64;
inline constexpr size_t kDefaultMaxReplaySenders = 4096;
// The environment variable that names the key file when no path is given.
inline constexpr char kAuthKeyFileEnv[] = "CONTACTSIM_AUTH_KEY_FILE";

// Reads a key file: its bytes with trailing whitespace removed. False (and
// `error` naming the file) when it cannot be read or the key is shorter
// than kMinAuthKeyBytes.
bool LoadAuthKey(const std::string& path, std::string* key, std::string* error);

// `path` if not empty, else $CONTACTSIM_AUTH_KEY_FILE, else "" (no signing).
std::string ResolveAuthKeyFile(const std::string& path);

// Wall-clock time in ns since the Unix epoch: the clock of seq.
uint64_t WallClockNanoseconds();

// The trailer for `payload` on `channel` with a given seq (deterministic;
// Signer::Sign picks the seq). 44 bytes.
std::string SignatureTrailer(const std::string& key, const std::string& channel, const void* payload, int size,
                             uint64_t seq);

// Signs messages of one sender. Thread-safe.
class Signer {
 public:
  explicit Signer(std::string key);
  // payload followed by its trailer, with seq = max(now, last seq + 1).
  std::string Sign(const std::string& channel, const void* payload, int size);
  uint64_t last_seq() const;

 private:
  uint64_t NextSeq();

  const std::string key_;
  mutable std::mutex mutex_;
  uint64_t last_seq_ = 0;
};

// The outcome of checking a message's mac. `error` starts with the name of
// the check that failed: "unsigned: ..." or "forged: ...".
struct Verified {
  bool ok = false;
  int payload_size = 0;  // bytes before the trailer (valid when ok)
  uint64_t seq = 0;      // the signed seq (valid when ok)
  std::string error;
};

// Checks the trailer and the mac (in constant time); freshness and replay
// are the receiver's ReplayWindow's job.
Verified VerifySignature(const std::string& key, const std::string& channel, const void* data, int size);

// True when `data` ends with something shaped like a trailer (the magic at
// size - 44); says nothing about the mac.
bool HasSignatureTrailer(const void* data, int size);

// The payload size of a message with its trailer (if any) stripped: what a
// receiver without a key decodes.
int UnsignedSize(const void* data, int size);

// True when |seq - now| <= window; otherwise `detail` says by how much,
// e.g. "signed 95.2 s ago, window 30 s".
bool CheckFreshness(uint64_t seq, uint64_t now_ns, double window_s, std::string* detail);

// Per-sender anti-replay state, as IPsec's (RFC 4303 section 3.4.3): the
// highest seq seen and a 64-wide bitmap of the seqs below it. Accepts a
// fresh seq above the highest, or within the 64 below it and not seen
// before. Holds at most `max_senders`, forgetting the least recently seen
// (its old messages are then still refused once they are stale). Thread-safe.
class ReplayWindow {
 public:
  explicit ReplayWindow(size_t max_senders = kDefaultMaxReplaySenders);
  // False with `why` ("stale: ..." or "replayed: ...") when refused; an
  // accepted seq is remembered.
  bool Accept(const std::string& sender, uint64_t seq, uint64_t now_ns, double window_s, std::string* why);
  size_t size() const;  // senders held

 private:
  struct Entry {
    uint64_t highest = 0;
    uint64_t seen = 0;  // bit i: seq highest - i was accepted
    std::list<std::string>::iterator recency;
  };
  bool AcceptInEntry(Entry* entry, uint64_t seq, std::string* why);
  Entry* Find(const std::string& sender);

  const size_t max_senders_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Entry> entries_;
  std::list<std::string> recency_;  // most recently seen first
};

}  // namespace contactsim
