#include "service/server/lcm_own_datagrams.h"

#include <arpa/inet.h>
#include <linux/filter.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

namespace contactsim {
namespace {

// The bound IPv4 port of a datagram socket; -1 for anything else.
int DatagramPort(int fd) {
  int type = 0;
  socklen_t len = sizeof type;
  if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0 || type != SOCK_DGRAM) return -1;
  sockaddr_in addr{};
  len = sizeof addr;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0 || addr.sin_family != AF_INET) return -1;
  return ntohs(addr.sin_port);
}

}  // namespace

bool ParseUdpmUrl(const std::string& url, int* port, int* ttl) {
  const std::string scheme = "udpm://";
  if (url.compare(0, scheme.size(), scheme) != 0) return false;
  const size_t colon = url.find(':', scheme.size());
  if (colon == std::string::npos) return false;
  *port = std::atoi(url.c_str() + colon + 1);
  *ttl = 0;  // LCM's default
  const size_t at = url.find("ttl=");
  if (at != std::string::npos) *ttl = std::atoi(url.c_str() + at + 4);
  return *port > 0;
}

Status FilterOwnDatagrams(int lcm_port) {
  rlimit limit{};
  const int max_fd = getrlimit(RLIMIT_NOFILE, &limit) == 0 ? static_cast<int>(std::min<rlim_t>(limit.rlim_cur, 4096))
                                                           : 1024;
  std::vector<int> receive, send;
  for (int fd = 0; fd < max_fd; ++fd) {
    const int port = DatagramPort(fd);
    if (port == lcm_port) receive.push_back(fd);
    if (port > 0 && port != lcm_port) send.push_back(fd);
  }
  if (receive.size() != 1 || send.size() != 1) {
    return Status::FailedPrecondition("found " + std::to_string(receive.size()) + " receive and " +
                                      std::to_string(send.size()) + " send socket(s) of LCM, not one each");
  }
  const int own_port = DatagramPort(send[0]);
  // ldh [0] (the UDP source port); if it is ours drop the datagram, else keep it whole
  sock_filter code[] = {
      BPF_STMT(BPF_LD | BPF_H | BPF_ABS, 0),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, static_cast<uint32_t>(own_port), 0, 1),
      BPF_STMT(BPF_RET | BPF_K, 0),
      BPF_STMT(BPF_RET | BPF_K, 0xFFFFFFFFu),
  };
  sock_fprog program{static_cast<unsigned short>(sizeof code / sizeof code[0]), code};
  if (setsockopt(receive[0], SOL_SOCKET, SO_ATTACH_FILTER, &program, sizeof program) != 0) {
    return Status::FailedPrecondition("SO_ATTACH_FILTER refused");
  }
  return Status::Ok();
}

}  // namespace contactsim
