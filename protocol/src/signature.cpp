// Signed LCM messages: the trailer, HMAC-SHA256 by libsodium, and the
// anti-replay window (docs/protocol.md, "Authentication").
#include "contactsim/signature.h"

#include <sodium.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace contactsim {
namespace {

// libsodium picks its SHA-256 implementation in sodium_init(); a failure
// there is a broken installation, not bad input, so it aborts (the
// always-on check for what is not the caller's fault) rather than signing wrongly.
void InitSodiumOnce() {
  static const bool ready = [] {
    if (sodium_init() < 0) {
      std::fprintf(stderr, "contactsim: sodium_init() failed; cannot sign or verify messages\n");
      std::abort();
    }
    return true;
  }();
  (void)ready;
}

void PutLittleEndian(uint64_t value, unsigned char* out) {
  for (int i = 0; i < 8; ++i) out[i] = static_cast<unsigned char>(value >> (8 * i));
}

uint64_t GetLittleEndian(const unsigned char* in) {
  uint64_t value = 0;
  for (int i = 7; i >= 0; --i) value = (value << 8) | in[i];
  return value;
}

// mac over channel || 0x00 || payload || magic || seq_le; the NUL keeps
// ("AB", "C...") and ("A", "BC...") apart.
void ComputeMac(const std::string& key, const std::string& channel, const void* payload, int size,
                const unsigned char* magic_and_seq, unsigned char* mac) {
  InitSodiumOnce();
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, reinterpret_cast<const unsigned char*>(key.data()), key.size());
  const unsigned char zero = 0;
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const unsigned char*>(channel.data()), channel.size());
  crypto_auth_hmacsha256_update(&state, &zero, 1);
  crypto_auth_hmacsha256_update(&state, static_cast<const unsigned char*>(payload), static_cast<size_t>(size));
  crypto_auth_hmacsha256_update(&state, magic_and_seq, kSignatureMagicBytes + 8);
  crypto_auth_hmacsha256_final(&state, mac);
  sodium_memzero(&state, sizeof(state));
}

std::string Seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", s);
  return text;
}

std::string WindowText(double window_s) {
  std::ostringstream text;
  text << window_s;
  return text.str();
}

}  // namespace

bool LoadAuthKey(const std::string& path, std::string* key, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = "cannot read auth key file \"" + path + "\": " + std::strerror(errno);
    return false;
  }
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) {
    *error = "cannot read auth key file \"" + path + "\"";
    return false;
  }
  const size_t end = bytes.find_last_not_of(" \t\r\n\v\f");
  bytes.resize(end == std::string::npos ? 0 : end + 1);
  if (bytes.size() < kMinAuthKeyBytes) {
    *error = "auth key file \"" + path + "\" holds a key of " + std::to_string(bytes.size()) +
             " bytes; at least " + std::to_string(kMinAuthKeyBytes) +
             " are needed (make one with: openssl rand -hex 32 > " + path + ")";
    return false;
  }
  *key = std::move(bytes);
  return true;
}

std::string ResolveAuthKeyFile(const std::string& path) {
  if (!path.empty()) return path;
  const char* env = std::getenv(kAuthKeyFileEnv);
  return env != nullptr ? env : "";
}

uint64_t WallClockNanoseconds() {
  const auto since_epoch = std::chrono::system_clock::now().time_since_epoch();
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(since_epoch).count());
}

std::string SignatureTrailer(const std::string& key, const std::string& channel, const void* payload, int size,
                             uint64_t seq) {
  unsigned char trailer[kSignatureTrailerBytes];
  std::memcpy(trailer, kSignatureMagic, kSignatureMagicBytes);
  PutLittleEndian(seq, trailer + kSignatureMagicBytes);
  ComputeMac(key, channel, payload, size, trailer, trailer + kSignatureMagicBytes + 8);
  return std::string(reinterpret_cast<const char*>(trailer), sizeof(trailer));
}

Signer::Signer(std::string key) : key_(std::move(key)) { InitSodiumOnce(); }

uint64_t Signer::NextSeq() {
  std::lock_guard<std::mutex> lock(mutex_);
  last_seq_ = std::max(WallClockNanoseconds(), last_seq_ + 1);
  return last_seq_;
}

uint64_t Signer::last_seq() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_seq_;
}

std::string Signer::Sign(const std::string& channel, const void* payload, int size) {
  std::string out(static_cast<const char*>(payload), static_cast<size_t>(size));
  out += SignatureTrailer(key_, channel, payload, size, NextSeq());
  return out;
}

bool HasSignatureTrailer(const void* data, int size) {
  return size >= kSignatureTrailerBytes &&
         std::memcmp(static_cast<const char*>(data) + size - kSignatureTrailerBytes, kSignatureMagic,
                     kSignatureMagicBytes) == 0;
}

int UnsignedSize(const void* data, int size) {
  return HasSignatureTrailer(data, size) ? size - kSignatureTrailerBytes : size;
}

Verified VerifySignature(const std::string& key, const std::string& channel, const void* data, int size) {
  Verified result;
  if (!HasSignatureTrailer(data, size)) {
    result.error = "unsigned: no signature trailer (\"CSG1\" at 44 bytes from the end of " + std::to_string(size) +
                   " bytes)";
    return result;
  }
  const int payload_size = size - kSignatureTrailerBytes;
  const auto* trailer = static_cast<const unsigned char*>(data) + payload_size;
  unsigned char mac[kSignatureMacBytes];
  ComputeMac(key, channel, data, payload_size, trailer, mac);
  static_assert(kSignatureMacBytes == crypto_verify_32_BYTES, "crypto_verify_32 compares 32 bytes");
  if (crypto_verify_32(mac, trailer + kSignatureMagicBytes + 8) != 0) {
    result.error = "forged: the signature does not match the key and the channel " + channel;
    return result;
  }
  result.ok = true;
  result.payload_size = payload_size;
  result.seq = GetLittleEndian(trailer + kSignatureMagicBytes);
  return result;
}

bool CheckFreshness(uint64_t seq, uint64_t now_ns, double window_s, std::string* detail) {
  // in double seconds: the difference of two u64 ns counts may not fit an int64
  const double age_s = (static_cast<double>(now_ns) - static_cast<double>(seq)) * 1e-9;
  if (std::fabs(age_s) <= window_s) return true;
  *detail = "signed " + Seconds(std::fabs(age_s)) + (age_s > 0 ? " s ago" : " s in the future") + ", window " +
            WindowText(window_s) + " s";
  return false;
}

ReplayWindow::ReplayWindow(size_t max_senders) : max_senders_(std::max<size_t>(1, max_senders)) {}

size_t ReplayWindow::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

ReplayWindow::Entry* ReplayWindow::Find(const std::string& sender) {
  auto it = entries_.find(sender);
  if (it == entries_.end()) return nullptr;
  recency_.splice(recency_.begin(), recency_, it->second.recency);  // now the most recent
  return &it->second;
}

bool ReplayWindow::AcceptInEntry(Entry* entry, uint64_t seq, std::string* why) {
  if (seq > entry->highest) {
    const uint64_t shift = seq - entry->highest;
    entry->seen = shift >= kReplayWindowSlots ? 1 : (entry->seen << shift) | 1;
    entry->highest = seq;
    return true;
  }
  const uint64_t below = entry->highest - seq;
  if (below >= kReplayWindowSlots) {
    *why = "replayed: seq " + std::to_string(seq) + " is more than " + std::to_string(kReplayWindowSlots) +
           " below the newest seen (" + std::to_string(entry->highest) + ")";
    return false;
  }
  const uint64_t bit = uint64_t{1} << below;
  if (entry->seen & bit) {
    *why = "replayed: seq " + std::to_string(seq) + " was seen before";
    return false;
  }
  entry->seen |= bit;
  return true;
}

bool ReplayWindow::Accept(const std::string& sender, uint64_t seq, uint64_t now_ns, double window_s,
                          std::string* why) {
  std::string detail;
  if (!CheckFreshness(seq, now_ns, window_s, &detail)) {
    *why = "stale: " + detail;
    return false;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (Entry* entry = Find(sender)) return AcceptInEntry(entry, seq, why);
  if (entries_.size() >= max_senders_) {
    entries_.erase(recency_.back());
    recency_.pop_back();
  }
  recency_.push_front(sender);
  Entry& entry = entries_[sender];
  entry.highest = seq;
  entry.seen = 1;
  entry.recency = recency_.begin();
  return true;
}

}  // namespace contactsim
