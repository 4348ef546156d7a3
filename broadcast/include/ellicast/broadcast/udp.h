// UDP transport: one ellicast packet per datagram, unicast or multicast, IPv4 or IPv6.
//
// The sender paces the carousel at a steady bit rate (counted over the ellicast packet bytes, not
// the UDP/IP headers). The receiver binds a port, joins a multicast group when the address is one,
// and hands every datagram to a caller; it never allocates per datagram beyond one fixed buffer.
#pragma once

#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/channel.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <sys/socket.h>

namespace ellicast::broadcast {

// An IPv4 or IPv6 address and port, e.g. "127.0.0.1:5000", "239.255.0.1:5000", "[::1]:5000",
// "[ff01::1%lo]:5000", "localhost:5000".
struct Endpoint {
    sockaddr_storage address{};
    socklen_t length = 0;
    std::string text;      // as the user wrote it
    bool ipv6() const { return address.ss_family == AF_INET6; }
    bool multicast() const;
    uint16_t port() const;
};

// Parses and resolves "HOST:PORT" / "[HOST]:PORT"; `error` says what is wrong.
bool parse_endpoint(const std::string& text, Endpoint& out, std::string& error);

struct SenderOptions {
    int multicast_ttl = 1;          // hops of multicast datagrams: 0 keeps them on this host
    bool multicast_loop = true;     // deliver multicast to receivers on this host too
    std::string interface;          // multicast interface name ("lo"); empty: the system's choice
};

class UdpSender {
public:
    UdpSender() = default;
    ~UdpSender();
    UdpSender(const UdpSender&) = delete;
    UdpSender& operator=(const UdpSender&) = delete;

    bool open(const Endpoint& to, const SenderOptions& options, std::string& error);
    // Sends one datagram. False with `error` when the system refuses it.
    bool send(std::span<const uint8_t> datagram, std::string& error);
    void close();

private:
    int fd_ = -1;
    Endpoint to_;
};

struct ReceiverOptions {
    std::string interface;            // multicast interface name to join on ("lo"); empty: default
    int receive_buffer_bytes = 4 << 20;  // SO_RCVBUF asked for, so bursts are not dropped
};

// What one receive() call got.
struct Datagram {
    size_t size = 0;          // bytes stored in the buffer
    bool truncated = false;   // the datagram was larger than the buffer (and was cut)
};

class UdpReceiver {
public:
    UdpReceiver() = default;
    ~UdpReceiver();
    UdpReceiver(const UdpReceiver&) = delete;
    UdpReceiver& operator=(const UdpReceiver&) = delete;

    // Binds the endpoint's port (on the group address for multicast, joining it) and listens.
    bool open(const Endpoint& listen, const ReceiverOptions& options, std::string& error);
    // Waits up to `timeout` for one datagram. Returns 1 with `out` filled, 0 on timeout,
    // -1 on a socket error (`error` says which).
    int receive(std::span<uint8_t> buffer, std::chrono::milliseconds timeout, Datagram& out, std::string& error);
    // The local port (useful after binding port 0).
    uint16_t local_port() const;
    void close();

private:
    int fd_ = -1;
};

// Spaces packets so that the bytes sent follow `bits_per_second` from the first packet on.
// A sender that falls behind by more than `max_lag` (e.g. after a stall) restarts its clock
// instead of bursting to catch up.
class Pacer {
public:
    explicit Pacer(double bits_per_second, std::chrono::milliseconds max_lag = std::chrono::milliseconds(50));
    // Sleeps until a packet of `bytes` bytes may go out, then accounts for it.
    void wait_to_send(size_t bytes);

private:
    double bits_per_second_;
    std::chrono::nanoseconds max_lag_;
    std::chrono::steady_clock::time_point start_{};
    double bits_ = 0;
    bool started_ = false;
};

struct ServeOptions {
    double bits_per_second = 1e6;
    double cycles = 1;                 // how many cycles to send (fractions allowed); <= 0: until stopped
    const LossTrace* trace = nullptr;  // sender-side simulated channel, applied by slot (or null)
    uint64_t first_slot = 0;           // slot number of the first packet sent
};

struct ServeCounters {
    uint64_t slots = 0;        // slots the schedule went through
    uint64_t datagrams = 0;    // datagrams actually sent (lost slots are not, duplicates twice)
    uint64_t bytes = 0;
    uint64_t dropped = 0;      // slots the simulated channel lost
    uint64_t corrupted = 0;
};

// Sends the carousel: slot by slot, paced, the trace (if any) deciding each slot's fate.
// `progress` is called about every 250 ms and at the end; `stop` ends the loop early when set.
bool serve_carousel(const Carousel& carousel, const std::vector<std::vector<uint8_t>>& packets, UdpSender& sender,
                    const ServeOptions& options, ServeCounters& counters, std::string& error,
                    const std::function<void(const ServeCounters&)>& progress = {},
                    const std::atomic<bool>* stop = nullptr);

}  // namespace ellicast::broadcast
