#include "service/server/rate_limiter.h"

#include <algorithm>

namespace contactsim {

RateLimiter::RateLimiter(double rate, double burst, size_t max_clients)
    : rate_(rate), burst_(std::max(1.0, burst)), max_clients_(max_clients), overflow_{burst_, Clock::now()} {}

bool RateLimiter::Take(Bucket* b, Clock::time_point now) {
  const double elapsed = std::chrono::duration<double>(now - b->last).count();
  b->tokens = std::min(burst_, b->tokens + std::max(0.0, elapsed) * rate_);
  b->last = now;
  if (b->tokens < 1.0) return false;
  b->tokens -= 1.0;
  return true;
}

void RateLimiter::DropRefilled(Clock::time_point now) {
  // a sweep costs the whole table: at most ten a second
  if (now - last_sweep_ < std::chrono::milliseconds(100)) return;
  last_sweep_ = now;
  for (auto it = buckets_.begin(); it != buckets_.end();) {
    const double elapsed = std::chrono::duration<double>(now - it->second.last).count();
    if (it->second.tokens + elapsed * rate_ >= burst_) {
      it = buckets_.erase(it);
    } else {
      ++it;
    }
  }
}

bool RateLimiter::Admit(const std::string& client, Clock::time_point now) {
  if (rate_ <= 0.0) return true;
  auto it = buckets_.find(client);
  if (it == buckets_.end()) {
    if (buckets_.size() >= max_clients_) DropRefilled(now);
    if (buckets_.size() >= max_clients_) return Take(&overflow_, now);
    it = buckets_.emplace(client, Bucket{burst_, now}).first;
  }
  return Take(&it->second, now);
}

}  // namespace contactsim
