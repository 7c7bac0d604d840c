// Keeps the server's own multicast datagrams out of its LCM receive socket.
//
// LCM's udpm transport sends to a multicast group with loopback on (other
// processes on this host must hear the server), so every STATE, JOINT_STATE
// and REPLY the server publishes also arrives at its own receive socket,
// where LCM's reader thread wakes, reads it and drops it (nobody in the
// server subscribes to it). A lockstep cycle publishes two datagrams and
// receives one input: two of the reader's three wake-ups a cycle were for
// the server's own datagrams, the largest single cost of an arm's cycle
// (BENCHMARKS.md, "Lockstep: the arm row").
//
// A classic BPF socket filter on the receive socket (socket(7),
// SO_ATTACH_FILTER) drops, in the kernel, the datagrams whose UDP source
// port is the server's send socket's. A UDP socket's filter sees the packet
// from its UDP header (Linux's udp_queue_rcv_one_skb), so the source port is
// the half-word at offset 0. Only with ttl=0, where every datagram comes from
// this host: with a larger ttl another host's sender could use the same
// port number.
#pragma once

#include <string>

#include "service/physics/status.h"

namespace contactsim {

// Finds the process's LCM sockets (the UDP socket bound to `lcm_port`
// receives; the other bound UDP socket sends) and filters the receive
// socket. FailedPrecondition when the two are not found as expected (the
// server then runs without the filter).
Status FilterOwnDatagrams(int lcm_port);

// The port and ttl of an udpm URL ("udpm://239.255.76.67:7667?ttl=0&...");
// false for another provider or an unreadable URL.
bool ParseUdpmUrl(const std::string& url, int* port, int* ttl);

}  // namespace contactsim
