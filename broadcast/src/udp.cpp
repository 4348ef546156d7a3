// UDP sockets (POSIX), the pacer, and the carousel sending loop.
#include <ellicast/broadcast/udp.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <deque>
#include <thread>

#include <arpa/inet.h>
#include <net/if.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <unistd.h>

namespace ellicast::broadcast {

namespace {

std::string system_error(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

bool Endpoint::multicast() const {
    if (address.ss_family == AF_INET) {
        auto* a = reinterpret_cast<const sockaddr_in*>(&address);
        return IN_MULTICAST(ntohl(a->sin_addr.s_addr));
    }
    if (address.ss_family == AF_INET6) {
        auto* a = reinterpret_cast<const sockaddr_in6*>(&address);
        return IN6_IS_ADDR_MULTICAST(&a->sin6_addr);
    }
    return false;
}

uint16_t Endpoint::port() const {
    if (address.ss_family == AF_INET) return ntohs(reinterpret_cast<const sockaddr_in*>(&address)->sin_port);
    if (address.ss_family == AF_INET6) return ntohs(reinterpret_cast<const sockaddr_in6*>(&address)->sin6_port);
    return 0;
}

bool parse_endpoint(const std::string& text, Endpoint& out, std::string& error) {
    out = Endpoint{};
    out.text = text;
    std::string host, port;
    if (!text.empty() && text[0] == '[') {
        auto close = text.find(']');
        if (close == std::string::npos || close + 1 >= text.size() || text[close + 1] != ':') {
            error = "\"" + text + "\" is not [IPV6]:PORT";
            return false;
        }
        host = text.substr(1, close - 1);
        port = text.substr(close + 2);
    } else {
        auto colon = text.rfind(':');
        if (colon == std::string::npos || text.find(':') != colon) {
            error = "\"" + text + "\" is not ADDRESS:PORT (write IPv6 addresses as [ADDRESS]:PORT)";
            return false;
        }
        host = text.substr(0, colon);
        port = text.substr(colon + 1);
    }
    if (host.empty()) {
        error = "\"" + text + "\" has no address";
        return false;
    }
    if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
        std::stoul(port) > 65535) {
        error = "\"" + port + "\" is not a port number (0..65535) in \"" + text + "\"";
        return false;
    }
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    hints.ai_flags = AI_NUMERICSERV;
    addrinfo* result = nullptr;
    int rc = getaddrinfo(host.c_str(), port.c_str(), &hints, &result);
    if (rc != 0 || result == nullptr) {
        error = "cannot resolve \"" + host + "\": " + gai_strerror(rc);
        return false;
    }
    std::memcpy(&out.address, result->ai_addr, result->ai_addrlen);
    out.length = result->ai_addrlen;
    freeaddrinfo(result);
    return true;
}

// ---------------------------------------------------------------------------------------------

UdpSender::~UdpSender() { close(); }

void UdpSender::close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

bool UdpSender::open(const Endpoint& to, const SenderOptions& options, std::string& error) {
    close();
    to_ = to;
    fd_ = ::socket(to.address.ss_family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) {
        error = system_error("cannot open a UDP socket");
        return false;
    }
    int send_buffer = 1 << 20;
    setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &send_buffer, sizeof send_buffer);
    if (to.multicast()) {
        if (options.multicast_ttl < 0 || options.multicast_ttl > 255) {
            error = "the multicast TTL must be 0..255";
            return false;
        }
        unsigned int index = 0;
        if (!options.interface.empty()) {
            index = if_nametoindex(options.interface.c_str());
            if (index == 0) {
                error = "no network interface named \"" + options.interface + "\"";
                return false;
            }
        }
        if (to.ipv6()) {
            int hops = options.multicast_ttl, loop = options.multicast_loop ? 1 : 0;
            if (setsockopt(fd_, IPPROTO_IPV6, IPV6_MULTICAST_HOPS, &hops, sizeof hops) != 0 ||
                setsockopt(fd_, IPPROTO_IPV6, IPV6_MULTICAST_LOOP, &loop, sizeof loop) != 0 ||
                (index && setsockopt(fd_, IPPROTO_IPV6, IPV6_MULTICAST_IF, &index, sizeof index) != 0)) {
                error = system_error("cannot set the IPv6 multicast options");
                return false;
            }
        } else {
            unsigned char ttl = static_cast<unsigned char>(options.multicast_ttl);
            unsigned char loop = options.multicast_loop ? 1 : 0;
            if (setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0 ||
                setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) {
                error = system_error("cannot set the IPv4 multicast options");
                return false;
            }
            if (index) {
                ip_mreqn request{};
                request.imr_ifindex = static_cast<int>(index);
                if (setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_IF, &request, sizeof request) != 0) {
                    error = system_error("cannot send multicast on " + options.interface);
                    return false;
                }
            }
        }
    }
    return true;
}

bool UdpSender::send(std::span<const uint8_t> datagram, std::string& error) {
    for (int attempt = 0; attempt < 100; ++attempt) {
        ssize_t n = ::sendto(fd_, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&to_.address),
                             to_.length);
        if (n == static_cast<ssize_t>(datagram.size())) return true;
        if (n < 0 && (errno == EINTR)) continue;
        if (n < 0 && (errno == ENOBUFS || errno == EAGAIN)) {
            // The socket buffer is full for a moment: wait a little rather than drop.
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            continue;
        }
        // A unicast receiver that is not (yet) listening makes the next send report
        // ECONNREFUSED on some systems: a one-way sender ignores it.
        if (n < 0 && errno == ECONNREFUSED) return true;
        error = system_error("sending to " + to_.text + " failed");
        return false;
    }
    error = "sending to " + to_.text + " failed: the socket stayed full";
    return false;
}

// ---------------------------------------------------------------------------------------------

UdpReceiver::~UdpReceiver() { close(); }

void UdpReceiver::close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

bool UdpReceiver::open(const Endpoint& listen, const ReceiverOptions& options, std::string& error) {
    close();
    fd_ = ::socket(listen.address.ss_family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) {
        error = system_error("cannot open a UDP socket");
        return false;
    }
    int yes = 1;
    if (listen.multicast()) {
        // Several receivers on one host may join the same group and port.
        setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    }
    int buffer = options.receive_buffer_bytes;
    setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
    if (listen.ipv6()) setsockopt(fd_, IPPROTO_IPV6, IPV6_V6ONLY, &yes, sizeof yes);
    // IPv6 multicast: bind the wildcard address on the group's port (binding a scoped group address
    // needs a scope id the user rarely gives); the membership then selects the group.
    sockaddr_storage bind_address = listen.address;
    if (listen.ipv6() && listen.multicast()) {
        auto* a = reinterpret_cast<sockaddr_in6*>(&bind_address);
        a->sin6_addr = in6addr_any;
        a->sin6_scope_id = 0;
    }
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&bind_address), listen.length) != 0) {
        error = system_error("cannot listen on " + listen.text);
        close();
        return false;
    }
    if (listen.multicast()) {
        unsigned int index = 0;
        if (!options.interface.empty()) {
            index = if_nametoindex(options.interface.c_str());
            if (index == 0) {
                error = "no network interface named \"" + options.interface + "\"";
                close();
                return false;
            }
        }
        int rc;
        if (listen.ipv6()) {
            ipv6_mreq request{};
            request.ipv6mr_multiaddr = reinterpret_cast<const sockaddr_in6*>(&listen.address)->sin6_addr;
            request.ipv6mr_interface = index;
            rc = setsockopt(fd_, IPPROTO_IPV6, IPV6_JOIN_GROUP, &request, sizeof request);
        } else {
            ip_mreqn request{};
            request.imr_multiaddr = reinterpret_cast<const sockaddr_in*>(&listen.address)->sin_addr;
            request.imr_ifindex = static_cast<int>(index);
            rc = setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &request, sizeof request);
        }
        if (rc != 0) {
            error = system_error("cannot join the multicast group " + listen.text +
                                 (options.interface.empty() ? "" : " on " + options.interface));
            close();
            return false;
        }
    }
    return true;
}

uint16_t UdpReceiver::local_port() const {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (fd_ < 0 || getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) return 0;
    if (address.ss_family == AF_INET) return ntohs(reinterpret_cast<sockaddr_in*>(&address)->sin_port);
    return ntohs(reinterpret_cast<sockaddr_in6*>(&address)->sin6_port);
}

int UdpReceiver::receive(std::span<uint8_t> buffer, std::chrono::milliseconds timeout, Datagram& out,
                         std::string& error) {
    out = Datagram{};
    pollfd p{fd_, POLLIN, 0};
    int ready = ::poll(&p, 1, static_cast<int>(std::max<int64_t>(0, timeout.count())));
    if (ready == 0 || (ready < 0 && errno == EINTR)) return 0;
    if (ready < 0) {
        error = system_error("waiting for datagrams failed");
        return -1;
    }
    // MSG_TRUNC makes recv return the datagram's real length even when it did not fit.
    ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), MSG_TRUNC | MSG_DONTWAIT);
    if (n < 0) {
        if (errno == EAGAIN || errno == EINTR || errno == ECONNREFUSED) return 0;
        error = system_error("receiving failed");
        return -1;
    }
    out.truncated = static_cast<size_t>(n) > buffer.size();
    out.size = std::min(static_cast<size_t>(n), buffer.size());
    return 1;
}

// ---------------------------------------------------------------------------------------------

Pacer::Pacer(double bits_per_second, std::chrono::milliseconds max_lag)
    : bits_per_second_(bits_per_second), max_lag_(max_lag) {}

void Pacer::wait_to_send(size_t bytes) {
    auto now = std::chrono::steady_clock::now();
    if (!started_) {
        started_ = true;
        start_ = now;
        bits_ = 0;
    }
    auto due = start_ + std::chrono::nanoseconds(static_cast<int64_t>(bits_ / bits_per_second_ * 1e9));
    if (due > now) {
        std::this_thread::sleep_until(due);
    } else if (now - due > max_lag_) {
        // Fell far behind: restart the clock here rather than burst.
        start_ = now;
        bits_ = 0;
    }
    bits_ += static_cast<double>(bytes) * 8.0;
}

bool serve_carousel(const Carousel& carousel, const std::vector<std::vector<uint8_t>>& packets, UdpSender& sender,
                    const ServeOptions& options, ServeCounters& counters, std::string& error,
                    const std::function<void(const ServeCounters&)>& progress, const std::atomic<bool>* stop) {
    counters = ServeCounters{};
    if (carousel.cycle.empty()) {
        error = "the carousel is empty";
        return false;
    }
    if (!(options.bits_per_second > 0)) {
        error = "the rate must be positive";
        return false;
    }
    const bool forever = !(options.cycles > 0);
    const uint64_t total = forever ? UINT64_MAX
                                   : static_cast<uint64_t>(std::ceil(options.cycles * carousel.slots_per_cycle()));
    Pacer pacer(options.bits_per_second);
    struct Held {
        uint64_t due;
        std::vector<uint8_t> bytes;
    };
    std::deque<Held> held;  // delayed datagrams, sent after the packet of their due slot
    auto last_report = std::chrono::steady_clock::now();
    for (uint64_t k = 0; k < total; ++k) {
        if (stop && stop->load()) break;
        const uint64_t slot = options.first_slot + k;
        std::vector<uint8_t> bytes = carousel_packet(carousel, packets, slot);
        pacer.wait_to_send(bytes.size());
        ++counters.slots;
        SlotFate fate;
        uint64_t trace_slot = 0;
        if (options.trace && options.trace->slots() > 0) {
            trace_slot = k % options.trace->slots();
            fate = options.trace->fate(trace_slot);
        }
        if (fate.lost) {
            ++counters.dropped;
        } else {
            if (fate.corrupted()) {
                bytes = damage_packet(*options.trace, trace_slot, bytes);
                ++counters.corrupted;
            }
            int copies = fate.duplicated ? 2 : 1;
            if (fate.delay > 0) {
                for (int c = 0; c < copies; ++c) {
                    Held h{k + fate.delay, bytes};
                    auto at = std::upper_bound(held.begin(), held.end(), h.due,
                                               [](uint64_t due, const Held& x) { return due < x.due; });
                    held.insert(at, std::move(h));
                }
            } else {
                for (int c = 0; c < copies; ++c) {
                    if (!sender.send(bytes, error)) return false;
                    ++counters.datagrams;
                    counters.bytes += bytes.size();
                }
            }
        }
        while (!held.empty() && held.front().due <= k) {
            if (!sender.send(held.front().bytes, error)) return false;
            ++counters.datagrams;
            counters.bytes += held.front().bytes.size();
            held.pop_front();
        }
        auto now = std::chrono::steady_clock::now();
        if (progress && now - last_report > std::chrono::milliseconds(250)) {
            progress(counters);
            last_report = now;
        }
    }
    for (auto& h : held) {
        if (!sender.send(h.bytes, error)) return false;
        ++counters.datagrams;
        counters.bytes += h.bytes.size();
    }
    if (progress) progress(counters);
    return true;
}

}  // namespace ellicast::broadcast
